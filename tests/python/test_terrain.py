"""Terrain input: rasters of heights read through GDAL as triangulated grids in metres, in
Python and on the command line."""
import subprocess
import sys

import pytest

import trichart
from trichart import tcArrayNames

DEM = "terrain/jacksboro_fault_dem_403x344.pgm"


def write_grid(path, rows, nodata=None):
    """An ESRI ASCII grid of 10 m cells at (500000, 4100000) (UTM-sized coordinates)."""
    header = (f"ncols {len(rows[0])}\nnrows {len(rows)}\nxllcorner 500000\n"
              f"yllcorner 4100000\ncellsize 10\n")
    if nodata is not None:
        header += f"NODATA_value {nodata}\n"
    path.write_text(header + "".join(" ".join(map(str, r)) + "\n" for r in rows))
    return path


def field(mesh, name):
    return mesh.GetFieldData().GetAbstractArray(name)


def report(mesh):
    """The reader's report, whose lines are the values of its string array."""
    lines = field(mesh, tcArrayNames.ReaderReport())
    return "\n".join(lines.GetValue(k) for k in range(lines.GetNumberOfValues()))


def test_a_grid_is_read_in_metres_around_its_first_cell(tmp_path):
    path = write_grid(tmp_path / "hill.asc", [[1, 2, 3], [4, 9, 6], [7, 8, 5]])
    mesh = trichart.read_mesh(path)
    assert mesh.GetNumberOfPoints() == 9 and mesh.GetNumberOfPolys() == 8
    # Positions are local: the first cell's centre is at the origin, the georeference apart.
    assert mesh.GetPoint(0) == (0.0, 0.0, 1.0)
    assert mesh.GetPoint(4) == (10.0, -10.0, 9.0)
    origin = field(mesh, tcArrayNames.GeoOrigin())
    assert origin.GetTuple2(0) == (500005.0, 4100025.0)
    assert mesh.GetPointData().GetArray(tcArrayNames.Elevation()).GetRange() == (1.0, 9.0)
    text = report(mesh)
    assert "height field of 3 x 3 cells" in text and "geotransform" in text


def test_no_data_cells_are_holes_and_the_vertical_scale_applies(tmp_path):
    path = write_grid(tmp_path / "holed.asc",
                      [[1, 2, 3], [4, -1, 6], [7, 8, 5]], nodata=-1)
    mesh = trichart.read_mesh(path, vertical_scale=3.0)
    assert mesh.GetNumberOfPoints() == 8
    assert mesh.GetNumberOfPolys() == 4  # each corner square keeps its 3 cells' triangle
    assert mesh.GetBounds()[4:] == (3.0, 24.0)
    assert mesh.GetPointData().GetArray(tcArrayNames.Elevation()).GetRange() == (1.0, 8.0)
    assert "1 cell without data left out as holes" in report(mesh)


def test_the_shared_dem_is_read_with_its_side_file(shared_data):
    mesh = trichart.read_mesh(shared_data / DEM)
    assert mesh.GetNumberOfPoints() == 403 * 344
    assert mesh.GetNumberOfPolys() == 2 * 402 * 343
    assert mesh.GetPointData().GetArray(tcArrayNames.Elevation()).GetRange() == (236.0, 1076.0)
    x0, x1, y0, y1, z0, z1 = mesh.GetBounds()
    # 403 x 344 cells of 3 arc-seconds at latitude 36.6: 30.0 km east-west, 31.7 km north-south.
    assert x1 - x0 == pytest.approx(402 * 74.57, rel=1e-3)
    assert y1 - y0 == pytest.approx(343 * 92.47, rel=1e-3)
    # The side file gives the raster's outer edges: the first cell's centre is half a cell in.
    lon, lat = field(mesh, tcArrayNames.GeoOrigin()).GetTuple2(0)
    assert lon == pytest.approx(-84.41375 + 0.5 / 1200)
    assert lat == pytest.approx(36.73291666666667 - 0.5 / 1200)
    assert "degrees, converted to metres" in report(mesh)


def test_what_is_no_raster_is_refused_with_the_file_named(tmp_path):
    bad = tmp_path / "scan.tif"
    bad.write_text("this is no TIFF")
    with pytest.raises(trichart.TriChartError, match="scan.tif"):
        trichart.read_mesh(bad)
    flat = write_grid(tmp_path / "empty.asc", [[0, 0], [0, 0]], nodata=0)
    with pytest.raises(trichart.TriChartError, match="no cell of data"):
        trichart.read_mesh(flat)


def run(*args):
    return subprocess.run([sys.executable, "-m", "trichart", *map(str, args)],
                          capture_output=True, text=True, timeout=300)


def test_the_command_line_reads_a_raster_with_a_vertical_scale(tmp_path):
    path = write_grid(tmp_path / "hill.asc", [[1, 2, 3], [4, 9, 6], [7, 8, 5]])
    out = tmp_path / "hill.vtp"
    r = run("prepare", path, "-o", out, "--vertical-scale", "2")
    assert r.returncode == 0, r.stderr
    mesh = trichart.read_mesh(out)
    assert mesh.GetNumberOfPolys() == 8 and mesh.GetBounds()[5] == 18.0
    r = run("prepare", path, "-o", out, "--vertical-scale", "0")
    assert r.returncode == 2 and "--vertical-scale must be above 0" in r.stderr
