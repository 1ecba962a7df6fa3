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


# 1. Sag: undeformed in grey, deformed (x100) coloured by |displacement|.
v = view_setup("Robot arm, service load (own weight + cable + payload): sag x %g" % SCALE)
d0 = Show(tube(arm, 0.012), v)
d0.DiffuseColor = [0.75, 0.75, 0.75]
d0.Opacity = 0.5
d0.ColorArrayName = ['POINTS', '']
warp = WarpByVector(Input=arm)
warp.Vectors = ["POINTS", "displacement"]
warp.ScaleFactor = SCALE
d1 = Show(tube(warp, 0.015), v)
ColorBy(d1, ("POINTS", "displacement", "Magnitude"))
lut = GetColorTransferFunction("displacement")
lut.ApplyPreset("Viridis (matplotlib)", True)
bar = GetScalarBar(lut, v)
bar.Title = "|u| (m)"
bar.ComponentTitle = ""
bar.TitleColor = [0, 0, 0]
bar.LabelColor = [0, 0, 0]
d1.SetScalarBarVisibility(v, True)
finish(v, os.path.join(here, "sag.png"), (0.62, 0.3), 0.4)

# 2. Bending moment My drawn across each member (diagram_My: My times the local z axis).
v2 = view_setup("Bending moment My along the members, service load (%g m per N m)" % MOMENT_SCALE)
b0 = Show(tube(arm, 0.008), v2)
b0.DiffuseColor = [0.3, 0.3, 0.3]
b0.ColorArrayName = ['POINTS', '']
dia = WarpByVector(Input=arm)
dia.Vectors = ["POINTS", "diagram_My"]
dia.ScaleFactor = MOMENT_SCALE
calc = Calculator(Input=dia)
calc.ResultArrayName = "My"
calc.Function = "section_forces_4"
b1 = Show(tube(calc, 0.006), v2)
ColorBy(b1, ("POINTS", "My"))
lut2 = GetColorTransferFunction("My")
lut2.ApplyPreset("Cool to Warm", True)
bar2 = GetScalarBar(lut2, v2)
bar2.Title = "My (N m)"
bar2.ComponentTitle = ""
bar2.TitleColor = [0, 0, 0]
bar2.LabelColor = [0, 0, 0]
b1.SetScalarBarVisibility(v2, True)
finish(v2, os.path.join(here, "moment.png"), (0.45, 0.55), 0.6)
# 3. The first vibration mode (analysis "modes"): the .vtu's displacement is the mode drawn at
# 10 % of the model size (results.json: vtk_scale); undeformed in grey.
mode = XMLUnstructuredGridReader(FileName=[os.path.join(out, "modes_mode1.vtu")])
mode.UpdatePipeline()
v3 = view_setup("First vibration mode, %.2f Hz (shape at 10 %% of the model size)" % mode.FieldData["frequency"].GetRange()[0])
m0 = Show(tube(mode, 0.012), v3)
m0.DiffuseColor = [0.75, 0.75, 0.75]
m0.Opacity = 0.5
m0.ColorArrayName = ['POINTS', '']
mw = WarpByVector(Input=mode)
mw.Vectors = ["POINTS", "displacement"]
mw.ScaleFactor = 1.0
m1 = Show(tube(mw, 0.015), v3)
ColorBy(m1, ("POINTS", "displacement", "Magnitude"))
lut3 = GetColorTransferFunction("displacement")
lut3.ApplyPreset("Viridis (matplotlib)", True)
finish(v3, os.path.join(here, "mode1.png"), (0.62, 0.35), 0.45)
print("wrote", os.path.join(here, "sag.png"), os.path.join(here, "moment.png"), "and", os.path.join(here, "mode1.png"))
