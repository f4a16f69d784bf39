"""Writers and readers of rotorcad's files: points CSV, DXF, meshes, STEP and the HTML report.

Every writer writes to a temporary file in the target folder and renames it into place only when
the whole group of files succeeded (:mod:`exports.atomic`), so a file is complete or absent and
an existing file is replaced whole or not at all (CONTRACT.md, common rules). The readers of
users' files (:mod:`exports.reading`, :mod:`exports.csv_points`, :mod:`exports.dxf_profile`)
refuse what they cannot read in one sentence.
"""
