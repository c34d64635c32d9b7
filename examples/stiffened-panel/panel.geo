// A 0.8 x 0.5 m CFRP skin with two aluminium stringers along x (y = -0.125 and
// y = +0.125), the stringers as curves embedded in the skin so that their beam
// elements share the skin's nodes. Physical groups: "skin" (surfaces),
// "stringers" (the two stringer curves), "root" (the edge x = -0.4, held),
// "fitting" (the tip corner, a point interface).
h = 0.04;
Point(1) = {-0.4, -0.25, 0, h}; Point(2) = {0.4, -0.25, 0, h};
Point(3) = {0.4, 0.25, 0, h};   Point(4) = {-0.4, 0.25, 0, h};
Point(5) = {-0.4, -0.125, 0, h}; Point(6) = {0.4, -0.125, 0, h};
Point(7) = {-0.4, 0.125, 0, h};  Point(8) = {0.4, 0.125, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 6}; Line(3) = {6, 8}; Line(4) = {8, 3};
Line(5) = {3, 4}; Line(6) = {4, 7}; Line(7) = {7, 5}; Line(8) = {5, 1};
Line(9) = {5, 6}; Line(10) = {7, 8};
Curve Loop(1) = {1, 2, -9, 8};   Plane Surface(1) = {1};
Curve Loop(2) = {9, 3, -10, 7};  Plane Surface(2) = {2};
Curve Loop(3) = {10, 4, 5, 6};   Plane Surface(3) = {3};
Physical Surface("skin") = {1, 2, 3};
Physical Curve("stringers") = {9, 10};
Physical Curve("root") = {6, 7, 8};
Physical Point("fitting") = {3};
