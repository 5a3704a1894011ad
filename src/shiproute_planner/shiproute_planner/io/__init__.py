"""Plan outputs: RTZ 1.2 route files, GeoJSON, JSON summary and PNG plots.

`RTZ_Schema_version_1_2.xsd` is the IEC 61174 RTZ 1.2 schema as distributed by CIRM
(http://www.cirm.org/RTZ/1/2), copied unchanged to validate written files.
"""
