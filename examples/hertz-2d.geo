// 2-D Hertz: the lower right quarter of a disc of radius R pressed on a rigid floor
// (examples/hertz-2d.json). h: element size at the top; the size falls linearly to
// h * contact_ratio at the contact point (0, 0), so the mesh is graded towards the contact.
// hertz-2d.msh is `gmsh -2 -clscale 1 hertz-2d.geo -o hertz-2d.msh` (Gmsh 4.8); other sizes
// scale h by S with `-clscale S` (scripts/amg_iterations.py). Gmsh 4.8's frontal quadrangle
// algorithm (8) crashes on this geometry: Frontal-Delaunay (6), recombined and subdivided.
R = 10;
h = 1;
contact_ratio = 0.1;
Point(1) = {0, 0, 0, h * contact_ratio};
Point(2) = {0, R, 0, h};
Point(3) = {R, R, 0, h};
Circle(1) = {1, 2, 3};
Line(2) = {3, 2};
Line(3) = {2, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Curve("arc") = {1};
Physical Curve("top") = {2};
Physical Curve("axis") = {3};
Physical Surface("body") = {1};
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;
Mesh.SubdivisionAlgorithm = 1;
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
