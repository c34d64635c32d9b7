#!/usr/bin/env python3
"""A layered solid model of the stiffened panel's bare skin for CalculiX 2.20
(tests/data/calculix/stiffened_panel; docs/validation.md, the stiffened-panel
row): NX x NY cells of C3D20R bricks, one brick per ply through the 2 mm
thickness, each brick with its ply's rectangular *ORIENTATION, the root face
x = -0.4 held (translations), *FREQUENCY 10. A reference for the skin that
needs neither shell theory: fe-prep's DST and CalculiX's expanded S8R are
both checked against it.

  python3 make_solid.py 32 20 0,45,-45,90,90,-45,45,0 qi32 && ccx -i qi32
  python3 make_solid.py 32 20 0,90,90,0 cp32 && ccx -i cp32     (a [0/90]s skin: 2 plies per brick of 0.5 mm)
"""
import math
import sys
NX,NY=int(sys.argv[1]),int(sys.argv[2])
angles=[int(a) for a in sys.argv[3].split(",")]
NZ=len(angles)
name=sys.argv[4]
LX,LY,H=0.8,0.5,0.002
# 20-node brick grid: nodes on a (2NX+1)x(2NY+1)x(2NZ+1) grid minus those with >=2 odd indices
nodes={}
for k in range(2*NZ+1):
  for j in range(2*NY+1):
    for i in range(2*NX+1):
      if (i%2)+(j%2)+(k%2)>=2: continue
      nodes[(i,j,k)]=len(nodes)+1
f=open(name+'.inp','w')
f.write('*NODE\n')
for (i,j,k),n in nodes.items():
  f.write('%d, %.12g, %.12g, %.12g\n'%(n,-LX/2+LX*i/(2*NX),-LY/2+LY*j/(2*NY),-H/2+H*k/(2*NZ)))
e=1
for L in range(NZ):
  f.write('*ELEMENT, TYPE=C3D20R, ELSET=L%d\n'%L)
  for J in range(NY):
    for I in range(NX):
      i,j,k=2*I,2*J,2*L
      c=[(i,j,k),(i+2,j,k),(i+2,j+2,k),(i,j+2,k),(i,j,k+2),(i+2,j,k+2),(i+2,j+2,k+2),(i,j+2,k+2),
         (i+1,j,k),(i+2,j+1,k),(i+1,j+2,k),(i,j+1,k),(i+1,j,k+2),(i+2,j+1,k+2),(i+1,j+2,k+2),(i,j+1,k+2),
         (i,j,k+1),(i+2,j,k+1),(i+2,j+2,k+1),(i,j+2,k+1)]
      ids=[nodes[x] for x in c]
      f.write('%d, %s,\n%s\n'%(e,', '.join(map(str,ids[:15])),', '.join(map(str,ids[15:]))))
      e+=1
f.write('*NSET, NSET=ROOT\n')
r=[n for (i,j,k),n in nodes.items() if i==0]
for a in range(0,len(r),8): f.write(', '.join(map(str,r[a:a+8]))+',\n')
f.write('*MATERIAL, NAME=IM6\n*ELASTIC, TYPE=ENGINEERING CONSTANTS\n177e9, 10.8e9, 10.8e9, 0.27, 0.27, 0.5, 7.6e9, 7.6e9,\n3.6e9, 0.\n*DENSITY\n1600\n')
for a in sorted(set(angles)):
  c,s=math.cos(math.radians(a)),math.sin(math.radians(a))
  f.write('*ORIENTATION, NAME=P%s, SYSTEM=RECTANGULAR\n%.17g,%.17g,0,%.17g,%.17g,0\n'%(str(a).replace('-','M'),c,s,-s,c))
for L in range(NZ):
  f.write('*SOLID SECTION, ELSET=L%d, MATERIAL=IM6, ORIENTATION=P%s\n'%(L,str(angles[L]).replace('-','M')))
f.write('*BOUNDARY\nROOT, 1, 3\n*STEP\n*FREQUENCY\n10\n*END STEP\n')
