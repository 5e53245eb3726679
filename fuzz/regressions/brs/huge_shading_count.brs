vertices 3
0 0 0
1 0 0
0 1 0
triangles 1
0 1 2
shading 4294967295
1.0
