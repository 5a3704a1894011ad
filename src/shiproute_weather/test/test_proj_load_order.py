"""GRIB (ecCodes) and geodesy (pyproj) in one process: the package loads PROJ in a working order."""

import subprocess
import sys


def test_pyproj_works_after_eccodes_when_the_package_is_imported_first():
    code = (
        "import shiproute_weather, eccodes, pyproj\n"
        "print(pyproj.CRS('EPSG:4979').name)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]  # also catches a crash at exit
    assert done.stdout.strip() == "WGS 84"
