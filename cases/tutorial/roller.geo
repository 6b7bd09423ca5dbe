// A steel roller (radius 10 mm) on a steel block, plane strain, the right half (x >= 0,
// symmetry about x = 0). The roller's lower quarter touches the block at the origin.
// Mesh (Tri6): gmsh -2 -order 2 -format msh41 roller.geo -o roller.msh
R = 10.0;     // roller radius (mm)
fine = 0.1;   // element size at the contact (mm)
coarse = 2.5; // elsewhere

// roller: centre (0, R), lowest point (0, 0)
Point(1) = {0, R, 0, coarse};     // centre
Point(2) = {0, 0, 0, fine};       // lowest point, on the axis
Point(3) = {R, R, 0, coarse};     // end of the arc
Line(1) = {1, 2};                 // axis
Circle(2) = {2, 1, 3};            // contact arc
Line(3) = {3, 1};                 // top, where the roller is pushed down
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// block: 2R wide, R deep; its top at y = 0 (its own corner point at the origin)
Point(4) = {0, 0, 0, fine};
Point(5) = {2*R, 0, 0, coarse};
Point(6) = {2*R, -R, 0, coarse};
Point(7) = {0, -R, 0, coarse};
Line(4) = {4, 5};                 // top face, the contact face
Line(5) = {5, 6};
Line(6) = {6, 7};                 // bottom, supported
Line(7) = {7, 4};                 // axis
Curve Loop(2) = {4, 5, 6, 7};
Plane Surface(2) = {2};

Physical Surface("Roller") = {1};
Physical Surface("Block") = {2};
Physical Curve("RollerAxis") = {1};
Physical Curve("Arc") = {2};
Physical Curve("RollerTop") = {3};
Physical Curve("Face") = {4};
Physical Curve("Bottom") = {6};
Physical Curve("BlockAxis") = {7};

// finer towards the contact along the arc and the face
Field[1] = Distance;
Field[1].PointsList = {2, 4};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = fine;
Field[2].SizeMax = coarse;
Field[2].DistMin = 0.8;
Field[2].DistMax = 8.0;
Background Field = 2;
