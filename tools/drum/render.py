# Renders a drum snapshot to PNG with ParaView: beads coloured by speed, the
# drum shell as an outline, looking along the drum axis.
#   xvfb-run -a pvbatch tools/drum/render.py post/drum_21rpm [--step N] [--out drum.png]
# (a ParaView built with offscreen rendering needs no xvfb-run)
import argparse
import glob
import os
import re
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, GetScalarBar,
                             LegacyVTKReader, Render, SaveScreenshot, Show, STLReader, XMLPolyDataReader)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("prefix", help="run prefix: bead files are <prefix>_<step>.vtp")
parser.add_argument("--step", type=int, help="time step to show (default: the last one)")
parser.add_argument("--out", help="PNG file (default: <prefix>.png)")
parser.add_argument("--size", type=int, default=1000, help="image width and height in pixels")
args = parser.parse_args()

pattern = re.compile(re.escape(os.path.basename(args.prefix)) + r"_(\d+)\.vtp$")
steps = sorted(int(m.group(1)) for f in glob.glob(args.prefix + "_*.vtp")
               for m in [pattern.search(os.path.basename(f))] if m)
if not steps:
    sys.exit("render: no files %s_<step>.vtp" % args.prefix)
step = args.step if args.step is not None else steps[-1]
if step not in steps:
    sys.exit("render: no step %d; available: %s" % (step, steps))

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [args.size, args.size]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
view.OrientationAxesVisibility = 0

beads = XMLPolyDataReader(FileName=["%s_%d.vtp" % (args.prefix, step)])
shown = Show(beads, view)
shown.SetRepresentationType("Point Gaussian")
shown.ScaleByArray = 1
shown.SetScaleArray = ["POINTS", "radius"]
shown.UseScaleFunction = 0  # radius array as is, not mapped to [0, 1]
shown.GaussianRadius = 1.0
shown.ShaderPreset = "Sphere"
ColorBy(shown, ("POINTS", "v", "Magnitude"))
speed = GetColorTransferFunction("v")
speed.ApplyPreset("Viridis (matplotlib)", True)
bar = GetScalarBar(speed, view)
bar.Title = "speed [m/s]"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
shown.SetScalarBarVisibility(view, True)

shell_file = "%s_shell_%d.vtk" % (args.prefix, step)
# the primitive cylinder writes no shell: its outline along the axis is any drum mesh's
drum_mesh = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "inputs", "meshes",
                         "drum_L6_N180.stl")
shell_source = (LegacyVTKReader(FileNames=[shell_file]) if os.path.exists(shell_file)
                else STLReader(FileNames=[drum_mesh]) if os.path.exists(drum_mesh) else None)
if shell_source is not None:
    shell = Show(shell_source, view)
    shell.SetRepresentationType("Feature Edges")
    shell.AmbientColor = shell.DiffuseColor = [0.2, 0.2, 0.2]
    shell.ColorArrayName = [None, ""]

# look along -x: y to the right, z (up, against gravity) upwards
view.CameraPosition = [1.5, 0.0, 0.0]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera()
Render(view)
out = args.out or args.prefix + ".png"
SaveScreenshot(out, view, ImageResolution=[args.size, args.size])
print("render: wrote %s (step %d)" % (out, step))
