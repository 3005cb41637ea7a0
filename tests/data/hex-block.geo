// A 1 x 1 x 0.5 block of 2 x 2 x 1 hexahedra (transfinite, recombined volume) for the
// end-to-end test of 3-D Gmsh meshes. Regenerate hex-block.msh with
//   gmsh -3 -format msh41 hex-block.geo -o hex-block.msh
SetFactory("Built-in");
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 2, 3, 4} = 3;
Transfinite Surface {1};
Recombine Surface {1};
out[] = Extrude {0, 0, 0.5} { Surface{1}; Layers{1}; Recombine; };
// out[0]: the top surface, out[1]: the volume, out[2..5]: the sides.
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("side_x0") = {out[5]};
Physical Surface("side_y0") = {out[2]};
Physical Volume("body") = {out[1]};
