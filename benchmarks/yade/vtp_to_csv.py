# Beads of one LIGGGHTS snapshot (.vtp from inputs/drum.in) as CSV for YADE:
# radius, position, velocity, angular velocity.
#   pvpython benchmarks/yade/vtp_to_csv.py IN.vtp OUT.csv
import sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy

reader = vtkXMLPolyDataReader()
reader.SetFileName(sys.argv[1])
reader.Update()
data = reader.GetOutput()
x = vtk_to_numpy(data.GetPoints().GetData())
pd = data.GetPointData()
r = vtk_to_numpy(pd.GetArray("radius"))
v = vtk_to_numpy(pd.GetArray("v"))
w = vtk_to_numpy(pd.GetArray("omega"))
with open(sys.argv[2], "w") as f:
    f.write("r,x,y,z,vx,vy,vz,wx,wy,wz\n")
    for i in range(len(r)):
        f.write("%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n" % ((r[i],) + tuple(x[i]) + tuple(v[i]) + tuple(w[i])))
print("%d beads" % len(r))
