"""What the pvpython tests share: checks that record a failure and go on, so that one run
reports every broken expectation."""
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAILED:", what)


def build_atlas(ns, mesh, atlas_file, reader_options=None, **images):
    """Runs the static pipeline of the plugin's proxies (in `ns`, where LoadPlugin put them) on
    `mesh` and writes the atlas to `atlas_file` with TriChart Atlas Writer; `reader_options`
    sets properties of TriChart Mesh Reader (e.g. BindPose), `images` of TriChart Geometry
    Images (e.g. SampleBudget). Returns the images proxy."""
    from paraview.simple import OutputPort, SaveData, UpdatePipeline
    reader = ns["TriChartMeshReader"](FileName=mesh, **(reader_options or {}))
    prep = ns["TriChartMeshPreparation"](Input=reader)
    curv = ns["TriChartCurvature"](Input=prep)
    clusters = ns["TriChartSpectralClustering"](Input=curv)
    features = ns["TriChartFeatureRefinement"](Input=clusters)
    base = ns["TriChartBaseComplex"](Input=features)
    paths = ns["TriChartPathTracing"](Input=OutputPort(base, 1))
    result = ns["TriChartGeometryImages"](Input=paths, **images)
    UpdatePipeline(proxy=result)
    SaveData(atlas_file, proxy=result)
    return result


def black_view(size=400):
    """A size x size render view on black without orientation axes, so that the lit pixels of
    its screenshot are the surface's (lit_pixels)."""
    from paraview.simple import CreateView
    view = CreateView("RenderView")
    view.ViewSize = [size, size]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    return view


def lit_mask(png_file, threshold=8):
    """(the indices of the pixels brighter than `threshold` in any colour channel, as a set,
    and the number of all pixels) of a PNG file."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    png = vtkPNGReader()
    png.SetFileName(png_file)
    png.Update()
    pixels = png.GetOutput().GetPointData().GetScalars()
    components = pixels.GetNumberOfComponents()
    total = pixels.GetNumberOfTuples()
    lit = {t for t in range(total)
           if any(pixels.GetValue(t * components + c) > threshold
                  for c in range(min(components, 3)))}
    return lit, total


def lit_pixels(png_file, threshold=8):
    """(pixels brighter than `threshold` in any colour channel, all pixels) of a PNG file."""
    lit, total = lit_mask(png_file, threshold)
    return len(lit), total
