#!/usr/bin/env python3
"""A layered solid model of the stiffened panel's skin for CalculiX 2.20
(tests/data/calculix/stiffened_panel; docs/validation.md, the stiffened-panel
row): NX x NY cells of 20-node bricks, one brick per entry of ANGLES through
the 2 mm thickness (a ply, or two equal plies of one angle), each brick with
its ply's rectangular *ORIENTATION, the root face x = -0.4 held
(translations), *FREQUENCY. A reference for the skin that needs neither
shell theory nor CalculiX's shell expansion: fe-prep's DST and CalculiX's
expanded S8R are both checked against it.

Optional, after the name:
  ELTYPE     C3D20R (default) or C3D20: the fully integrated brick, exact
             (27 points) on these rectangular bricks, with the consistent
             mass: its eigenvalues are upper bounds of the 3-D elasticity
             eigenvalues of the same clamped plate (min-max principle)
  stringers  the two 4 x 25 mm aluminium blades of make_decks.py as B32R
             beams (SECTION=RECT, 1-direction z) on their own nodes along
             y = -0.125 and +0.125 at z = 0, each node's translations tied
             by *EQUATION to the solid's mid-plane node it lies on (rotations
             free), the beams' root nodes clamped: make_decks.py's stiffened
             panel with the S8R skin replaced by the layered solid (the
             mid-plane z = 0 is a ply interface, so it carries corner nodes)

  python3 make_solid.py 32 20 0,45,-45,90,90,-45,45,0 qi32 && ccx -i qi32
  python3 make_solid.py 32 20 0,90,90,0 cp32 && ccx -i cp32     (a [0/90]s skin: 2 plies per brick of 0.5 mm)
  python3 make_solid.py 32 20 0,45,-45,90,90,-45,45,0 qis32 C3D20 stringers   (the stiffened panel, 3-D skin)
"""
import math
import sys
from make_decks import ccx_num
NX,NY=int(sys.argv[1]),int(sys.argv[2])
angles=[int(a) for a in sys.argv[3].split(",")]
NZ=len(angles)
name=sys.argv[4]
opts=sys.argv[5:]
eltype=opts[0] if opts and opts[0].startswith('C3D') else 'C3D20R'
stringers='stringers' in opts
LX,LY,H=0.8,0.5,0.002
YS,BW,BH=0.125,0.004,0.025
assert not stringers or (NZ%2==0 and NY%4==0), "stringers need a mid-plane interface (even brick count) and NY a multiple of 4"
# 20-node brick grid: nodes on a (2NX+1)x(2NY+1)x(2NZ+1) grid minus those with >=2 odd indices
nodes={}
for k in range(2*NZ+1):
  for j in range(2*NY+1):
    for i in range(2*NX+1):
      if (i%2)+(j%2)+(k%2)>=2: continue
      nodes[(i,j,k)]=len(nodes)+1
xyz=lambda i,j,k:(-LX/2+LX*i/(2*NX),-LY/2+LY*j/(2*NY),-H/2+H*k/(2*NZ))
f=open(name+'.inp','w')
f.write('*NODE\n')
for (i,j,k),n in nodes.items():
  f.write('%d, %s, %s, %s\n'%((n,)+tuple(ccx_num(v) for v in xyz(i,j,k))))
e=1
for L in range(NZ):
  f.write('*ELEMENT, TYPE=%s, ELSET=L%d\n'%(eltype,L))
  for J in range(NY):
    for I in range(NX):
      i,j,k=2*I,2*J,2*L
      c=[(i,j,k),(i+2,j,k),(i+2,j+2,k),(i,j+2,k),(i,j,k+2),(i+2,j,k+2),(i+2,j+2,k+2),(i,j+2,k+2),
         (i+1,j,k),(i+2,j+1,k),(i+1,j+2,k),(i,j+1,k),(i+1,j,k+2),(i+2,j+1,k+2),(i+1,j+2,k+2),(i,j+1,k+2),
         (i,j,k+1),(i+2,j,k+1),(i+2,j+2,k+1),(i,j+2,k+1)]
      ids=[nodes[x] for x in c]
      f.write('%d, %s,\n%s\n'%(e,', '.join(map(str,ids[:15])),', '.join(map(str,ids[15:]))))
      e+=1
def nset(setname,ids):
  f.write('*NSET, NSET=%s\n'%setname)
  for a in range(0,len(ids),8): f.write(', '.join(map(str,ids[a:a+8]))+',\n')
nset('ROOT',[n for (i,j,k),n in nodes.items() if i==0])
if stringers:
  beam={}
  nn=len(nodes)
  for j in (NY//2,3*NY//2):
    for i in range(2*NX+1):
      beam[(i,j)]=nn+1+len(beam)
  f.write('*NODE, NSET=NSTR\n')
  for (i,j),n in beam.items():
    f.write('%d, %s, %s, 0\n'%((n,)+tuple(ccx_num(v) for v in xyz(i,j,NZ)[:2])))
  f.write('*ELEMENT, TYPE=B32R, ELSET=STR\n')
  for j in (NY//2,3*NY//2):
    for I in range(NX):
      f.write('%d, %d, %d, %d\n'%(e,beam[(2*I,j)],beam[(2*I+1,j)],beam[(2*I+2,j)]))
      e+=1
  # translations tied, rotations free (make_decks.py's tie, here to the mid-plane nodes)
  f.write('*EQUATION\n')
  for (i,j),n in beam.items():
    if i==0: continue
    for d in (1,2,3):
      f.write('2\n%d, %d, 1., %d, %d, -1.\n'%(n,d,nodes[(i,j,NZ)],d))
  nset('BROOT',[n for (i,j),n in beam.items() if i==0])
f.write('*MATERIAL, NAME=IM6\n*ELASTIC, TYPE=ENGINEERING CONSTANTS\n177e9, 10.8e9, 10.8e9, 0.27, 0.27, 0.5, 7.6e9, 7.6e9,\n3.6e9, 0.\n*DENSITY\n1600\n')
if stringers:
  f.write('*MATERIAL, NAME=ALU\n*ELASTIC\n70e9, 0.33\n*DENSITY\n2700\n')
for a in sorted(set(angles)):
  c,s=math.cos(math.radians(a)),math.sin(math.radians(a))
  # make_decks.ccx_num: CalculiX reads a number's first 20 characters only
  f.write('*ORIENTATION, NAME=P%s, SYSTEM=RECTANGULAR\n%s,%s,0,%s,%s,0\n'%((str(a).replace('-','M'),)+tuple(ccx_num(v) for v in (c,s,-s,c))))
for L in range(NZ):
  f.write('*SOLID SECTION, ELSET=L%d, MATERIAL=IM6, ORIENTATION=P%s\n'%(L,str(angles[L]).replace('-','M')))
if stringers:
  f.write('*BEAM SECTION, ELSET=STR, MATERIAL=ALU, SECTION=RECT\n%g, %g\n0., 0., 1.\n'%(BH,BW))
f.write('*BOUNDARY\nROOT, 1, 3\n')
if stringers:
  f.write('BROOT, 1, 6\n')
f.write('*STEP\n*FREQUENCY\n%d\n*END STEP\n'%(12 if stringers else 10))
