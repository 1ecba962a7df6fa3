# Renders the arm's sag under the service load case and its bending-moment diagram with ParaView.
#   beamfea run model.json --out ../../out/09_robot_arm_self_weight
#   xvfb-run -a pvbatch render.py ../../out/09_robot_arm_self_weight
# writes sag.png, moment.png and mode1.png next to this script.
import os
import sys

from paraview.simple import *  # noqa: F401,F403

out = sys.argv[1] if len(sys.argv) > 1 else "../../out/09_robot_arm_self_weight"
here = os.path.dirname(os.path.abspath(__file__))
vtu = os.path.join(out, "sag_service.vtu")
arm = XMLUnstructuredGridReader(FileName=[vtu])
arm.UpdatePipeline()

# Sag magnified so that millimetres show on a metre-long arm.
SCALE = 100.0
MOMENT_SCALE = 2.0e-3  # metres per N m for the diagram


def view_setup(title):
    v = CreateView("RenderView")
    v.ViewSize = [1400, 700]
    v.UseColorPaletteForBackground = 0
    v.Background = [1, 1, 1]
    v.OrientationAxesVisibility = 1
    v.OrientationAxesLabelColor = [0, 0, 0]
    t = Text(Text=title)
    td = Show(t, v)
    td.FontSize = 14
    td.Color = [0, 0, 0]
    td.WindowLocation = "Upper Center"
    return v


def tube(src, radius):
    t = Tube(Input=ExtractSurface(Input=src))
    t.Radius = radius
    t.NumberofSides = 16
    return t


def finish(v, path, focal, scale):
    Render(v)
    v.CameraPosition = [focal[0], -3.5, focal[1]]
    v.CameraFocalPoint = [focal[0], 0.0, focal[1]]
    v.CameraViewUp = [0, 0, 1]
    v.CameraParallelProjection = 1
    v.CameraParallelScale = scale
    Render(v)
    SaveScreenshot(path, v, ImageResolution=[1400, 700])


def plain(src, v, radius, grey, opacity=1.0):
    """The members as uncoloured tubes (the undeformed arm under a deformed one)."""
    d = Show(tube(src, radius), v)
    d.DiffuseColor = [grey] * 3
    d.Opacity = opacity
    d.ColorArrayName = ['POINTS', '']


def coloured(src, v, radius, array, preset, bar_title=None, component=None):
    """Tubes coloured by a point array (its magnitude when `component` is "Magnitude")."""
    d = Show(tube(src, radius), v)
    ColorBy(d, ("POINTS", array, component) if component else ("POINTS", array))
    lut = GetColorTransferFunction(array)
    lut.ApplyPreset(preset, True)
    if bar_title:
        bar = GetScalarBar(lut, v)
        bar.Title = bar_title
        bar.ComponentTitle = ""
        bar.TitleColor = [0, 0, 0]
        bar.LabelColor = [0, 0, 0]
        d.SetScalarBarVisibility(v, True)


def warped(src, vectors, scale):
    w = WarpByVector(Input=src)
    w.Vectors = ["POINTS", vectors]
    w.ScaleFactor = scale
    return w


# 1. Sag: undeformed in grey, deformed (x100) coloured by |displacement|.
v = view_setup("Robot arm, service load (own weight + cable + payload): sag x %g" % SCALE)
plain(arm, v, 0.012, 0.75, opacity=0.5)
coloured(warped(arm, "displacement", SCALE), v, 0.015, "displacement", "Viridis (matplotlib)", "|u| (m)", "Magnitude")
finish(v, os.path.join(here, "sag.png"), (0.62, 0.3), 0.4)

# 2. Bending moment My drawn across each member (diagram_My: My times the local z axis).
v2 = view_setup("Bending moment My along the members, service load (%g m per N m)" % MOMENT_SCALE)
plain(arm, v2, 0.008, 0.3)
calc = Calculator(Input=warped(arm, "diagram_My", MOMENT_SCALE))
calc.ResultArrayName = "My"
calc.Function = "section_forces_4"
coloured(calc, v2, 0.006, "My", "Cool to Warm", "My (N m)")
finish(v2, os.path.join(here, "moment.png"), (0.45, 0.55), 0.6)

# 3. The first vibration mode (analysis "modes"): the .vtu's displacement is the mode drawn at
# 10 % of the model size (results.json: vtk_scale); undeformed in grey.
mode = XMLUnstructuredGridReader(FileName=[os.path.join(out, "modes_mode1.vtu")])
mode.UpdatePipeline()
v3 = view_setup("First vibration mode, %.2f Hz (shape at 10 %% of the model size)" % mode.FieldData["frequency"].GetRange()[0])
plain(mode, v3, 0.012, 0.75, opacity=0.5)
coloured(warped(mode, "displacement", 1.0), v3, 0.015, "displacement", "Viridis (matplotlib)", component="Magnitude")
finish(v3, os.path.join(here, "mode1.png"), (0.62, 0.35), 0.45)
print("wrote", os.path.join(here, "sag.png"), os.path.join(here, "moment.png"), "and", os.path.join(here, "mode1.png"))
