"""The ``rotorcad`` command line (CONTRACT.md). Only this package reads files and prints."""
