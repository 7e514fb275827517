// Two elastic blocks touching on the plane z = 0: body 1 above, body 2 below.
//
// The scene of fem_validation: Hertz's own problem, two half-spaces with the
// quadratic initial gap h(x, y) = (x, y) S (x, y)^T / 2 between their flat
// faces (S is imposed by the solver, not by this geometry), truncated to
// blocks.  The parameters below are set by fem_validation/mesh.py through
// ONELAB; opened in the Gmsh GUI this file meshes a default scene (an
// elliptical contact with semi-axes 2 x 1 in a quarter model).
//
// Lengths are in units of the contact's minor semi-axis b.
//
// The mesh has two parts:
//  * a structured block around the contact on each side of z = 0, covering
//    zone times the semi-axes in the plane of the contact (in the ellipse's
//    frame) and zi deep: a grid of spacing hs across the major axis and in
//    depth, st * hs along it (st > 1 for elongated contacts), each cell cut
//    into 6 tetrahedra.  Identical node patches make the node-to-node
//    contact pressure smooth (an unstructured mesh adds a node-to-node
//    scatter of 2% of p0 at hs = 0.07 b);
//  * unstructured tetrahedra elsewhere (HXT), of size h0 down to depth zz
//    below the contact zone, growing by `grade` per unit distance from it,
//    capped at hmax.

SetFactory("OpenCASCADE");

DefineConstant[
  L = {80, Name "Parameters/L", Help "lateral half-width of each block"},
  H = {80, Name "Parameters/H", Help "depth of each block"},
  quarter = {1, Choices {0, 1}, Name "Parameters/quarter",
             Help "1: keep x >= 0, y >= 0 (symmetry planes); 0: full blocks"},
  ea = {2, Name "Parameters/ea", Help "semi-major axis of the expected contact ellipse"},
  eb = {1, Name "Parameters/eb", Help "its semi-minor axis"},
  etheta = {0, Name "Parameters/etheta",
            Help "angle of its major axis from x [rad] (0 or pi/2 for a quarter model)"},
  zone = {1.25, Name "Parameters/zone", Help "structured block: semi-axes times this"},
  zi = {1.0, Name "Parameters/zi", Help "depth of the structured block"},
  hs = {0.1, Name "Parameters/hs", Help "its spacing across the major axis and in depth"},
  st = {1, Name "Parameters/st", Help "its spacing along the major axis over hs"},
  zz = {1.3, Name "Parameters/zz", Help "depth of the zone of size h0"},
  h0 = {0.14, Name "Parameters/h0", Help "element size around the structured block"},
  grade = {0.2, Name "Parameters/grade", Help "growth of the size away from the zone"},
  hmax = {8, Name "Parameters/hmax", Help "largest element size"}
];

c = Cos(etheta);
s = Sin(etheta);
XI = zone * ea;  // structured block's half-lengths in the ellipse's frame
YI = zone * eb;
x0 = quarter ? 0 : -L;
y0 = quarter ? 0 : -L;
Box(1) = {x0, y0, 0, L - x0, L - y0, H};
Box(2) = {x0, y0, -H, L - x0, L - y0, H};
If (quarter)
  // x >= 0, y >= 0; the z axis is the edge x = y = 0.
  xi = (Fabs(s) < 1e-9) ? XI : YI;  // the block's half-lengths along x and y
  yi = (Fabs(s) < 1e-9) ? YI : XI;
  Box(3) = {0, 0, 0, xi, yi, zi};
  Box(4) = {0, 0, -zi, xi, yi, zi};
  BooleanFragments{ Volume{1, 2}; Delete; }{ Volume{3, 4}; Delete; }
Else
  // Whole blocks: the structured block is made of 4 quadrants on each side,
  // so that the z axis is a line of nodes; it is embedded below them.
  For q In {0:3}
    Box(3 + q) = {(q == 1 || q == 2) ? -XI : 0, (q >= 2) ? -YI : 0, -zi, XI, YI, zi};
    Box(7 + q) = {(q == 1 || q == 2) ? -XI : 0, (q >= 2) ? -YI : 0, 0, XI, YI, zi};
  EndFor
  Rotate {{0, 0, 1}, {0, 0, 0}, etheta} { Volume{3:10}; }
  Point(1001) = {0, 0, -H};
  Point(1002) = {0, 0, H};
  Line(1001) = {1001, 1002};
  BooleanFragments{ Volume{1, 2}; Delete; }{ Volume{3:10}; Line{1001}; Delete; }
EndIf

e = 1e-6 * L;  // bounding-box tolerance (OCC boxes are padded)
Physical Volume("body1") = Volume In BoundingBox{x0 - e, y0 - e, -e, L + e, L + e, H + e};
Physical Volume("body2") = Volume In BoundingBox{x0 - e, y0 - e, -H - e, L + e, L + e, e};
Physical Surface("contact") = Surface In BoundingBox{x0 - e, y0 - e, -e, L + e, L + e, e};
Physical Surface("top") = Surface In BoundingBox{x0 - e, y0 - e, H - e, L + e, L + e, H + e};
Physical Surface("bottom") = Surface In BoundingBox{x0 - e, y0 - e, -H - e, L + e, L + e,
                                                   -H + e};
Physical Curve("axis") = Curve In BoundingBox{-e, -e, -H - e, e, e, H + e};
If (quarter)
  Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -H - e, e, L + e, H + e};
  Physical Surface("sym_y") = Surface In BoundingBox{-e, -e, -H - e, L + e, e, H + e};
EndIf

// The structured block: every curve inside it gets its number of cells from
// its direction in the ellipse's frame.
r = Sqrt(XI^2 + YI^2) + e;
lo = quarter ? -e : -r;
cells() = Curve In BoundingBox{lo, lo, -zi - e, r, r, zi + e};
For i In {0:#cells() - 1}
  ends() = PointsOf{ Curve{cells(i)}; };
  p() = Point{ends(0)};
  q() = Point{ends(1)};
  along = Fabs((q(0) - p(0)) * c + (q(1) - p(1)) * s);
  across = Fabs((q(1) - p(1)) * c - (q(0) - p(0)) * s);
  If (along > e)
    Transfinite Curve{cells(i)} = Ceil(along / (st * hs) - 1e-9) + 1;
  ElseIf (across > e)
    Transfinite Curve{cells(i)} = Ceil(across / hs - 1e-9) + 1;
  Else
    Transfinite Curve{cells(i)} = Ceil(zi / hs - 1e-9) + 1;
  EndIf
EndFor
Transfinite Surface{Surface In BoundingBox{lo, lo, -zi - e, r, r, zi + e}};
Transfinite Volume{Volume In BoundingBox{lo, lo, -zi - e, r, r, zi + e}};

// Element size elsewhere, with (X, Y) the coordinates in the ellipse's frame:
// h0 in the zone |X| <= zone ea, |Y| <= zone eb, |z| <= zz, growing by
// `grade` per unit distance from it, capped at hmax.
X = Sprintf("(x * (%g) + y * (%g))", c, s);
Y = Sprintf("(y * (%g) - x * (%g))", c, s);
Field[1] = MathEval;
Field[1].F = Sprintf(StrCat("Min(%g, %g + %g * Sqrt(Max(Abs(", X, ") - %g, 0)^2",
                            " + Max(Abs(", Y, ") - %g, 0)^2 + Max(Abs(z) - %g, 0)^2))"),
                     hmax, h0, grade, XI, YI, zz);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 10;  // HXT: 5-10x faster than Delaunay here, deterministic on one thread
General.NumThreads = 1;  // deterministic meshes
Mesh.RandomSeed = 1;
