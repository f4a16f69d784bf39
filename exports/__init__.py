"""Writers and readers of rotorcad's files: points CSV, DXF, and (later) meshes and STEP.

Every writer writes to a temporary file in the target folder and renames it into place only when
the whole group of files succeeded (:mod:`exports.atomic`), so a file is complete or absent and
an existing file is replaced whole or not at all (CONTRACT.md, common rules).
"""
