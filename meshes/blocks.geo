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

SetFactory("OpenCASCADE");

DefineConstant[
  L = {40, Name "Parameters/L", Help "lateral half-width of each block"},
  H = {40, Name "Parameters/H", Help "depth of each block"},
  quarter = {1, Choices {0, 1}, Name "Parameters/quarter",
             Help "1: keep x >= 0, y >= 0 (symmetry planes); 0: full blocks"},
  ea = {2, Name "Parameters/ea", Help "semi-major axis of the expected contact ellipse"},
  eb = {1, Name "Parameters/eb", Help "its semi-minor axis"},
  etheta = {0, Name "Parameters/etheta", Help "angle of its major axis from x [rad]"},
  zone = {1.2, Name "Parameters/zone", Help "refined zone: elliptical radius it reaches"},
  rz = {0.6, Name "Parameters/rz", Help "depth of the refined zone on each side"},
  h0 = {0.1, Name "Parameters/h0", Help "element size in the refined zone"},
  he = {0.05, Name "Parameters/he", Help "element size at the ellipse's edge on z = 0"},
  grade = {0.3, Name "Parameters/grade", Help "growth of the size away from the zone"},
  ge = {0.5, Name "Parameters/ge", Help "growth of the size away from the edge"},
  hmax = {8, Name "Parameters/hmax", Help "largest element size"}
];

x0 = quarter ? 0 : -L;
y0 = quarter ? 0 : -L;
Box(1) = {x0, y0, 0, L - x0, L - y0, H};
Box(2) = {x0, y0, -H, L - x0, L - y0, H};
// One shared face at z = 0, so both meshes match there; the solver gives each
// body its own copy of those nodes.
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }

e = 1e-6 * L;  // bounding-box tolerance (OCC boxes are padded)
Physical Volume("body1") = Volume In BoundingBox{x0 - e, y0 - e, -e, L + e, L + e, H + e};
Physical Volume("body2") = Volume In BoundingBox{x0 - e, y0 - e, -H - e, L + e, L + e, e};
Physical Surface("contact") = Surface In BoundingBox{x0 - e, y0 - e, -e, L + e, L + e, e};
Physical Surface("top") = Surface In BoundingBox{x0 - e, y0 - e, H - e, L + e, L + e, H + e};
Physical Surface("bottom") = Surface In BoundingBox{x0 - e, y0 - e, -H - e, L + e, L + e, -H + e};
If (quarter)
  Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -H - e, e, L + e, H + e};
  Physical Surface("sym_y") = Surface In BoundingBox{-e, -e, -H - e, L + e, e, H + e};
EndIf

// Sizes use the elliptical radius r of the expected contact ellipse (r = 1 on
// its edge) and the distance from it measured in units of eb:
//   h0 where r <= zone and |z| <= rz, growing by `grade` per unit distance
//   beyond, capped at hmax; and he on the ellipse's edge at z = 0, growing by
//   `ge`, where the pressure falls to zero with infinite slope.
c = Cos(etheta);
s = Sin(etheta);
Field[1] = MathEval;
Field[1].F = Sprintf(StrCat("Min(%g, %g + %g * Sqrt((%g * Max(",
                            "Sqrt(((x * (%g) + y * (%g)) / %g)^2 + ((y * (%g) - x * (%g)) / %g)^2)",
                            " - %g, 0))^2 + Max(Abs(z) - %g, 0)^2))"),
                     hmax, h0, grade, eb, c, s, ea, c, s, eb, zone, rz);
Field[2] = MathEval;
Field[2].F = Sprintf(StrCat("%g + %g * Sqrt((%g * (",
                            "Sqrt(((x * (%g) + y * (%g)) / %g)^2 + ((y * (%g) - x * (%g)) / %g)^2)",
                            " - 1))^2 + z^2)"),
                     he, ge, eb, c, s, ea, c, s, eb);
Field[3] = Min;
Field[3].FieldsList = {1, 2};
Background Field = 3;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
