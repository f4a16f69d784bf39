"""Old path of the defensive reading of a user's file: it moved to :mod:`rotorcad.design.reading`."""

from rotorcad.design.reading import MAX_BYTES, check_regular_file, read_bytes, read_text

__all__ = ["MAX_BYTES", "check_regular_file", "read_bytes", "read_text"]
