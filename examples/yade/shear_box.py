# Faultline example: a small bonded (cohesive) granular block sheared between two rigid grips (Yade).
#
# About 1,000 spheres (mean radius 0.75 mm, +-30 %) fill a 30 x 10 x 16 mm box
# (pack.randomDensePack, periodic compression, fixed seed). Neighbours are bonded with
# CohFrictMat / Law2_ScGeom6D_CohFrictPhys_CohesionMoment. The bottom two grain layers are held
# fixed, the top two layers move in +x at a constant speed, so the block is sheared
# (about 4 % shear strain at the end) and bonds break along shear bands.
#
# Run from this folder (batch mode, no GUI):
#     yade -n -x shear_box.py
# Output goes to ./out/ (created if missing), 3 snapshots (start, middle, end of shearing):
#     shear-spheres-0000000N.vtk   yade.export.VTKExporter.exportSpheres  (VTK legacy POLYDATA)
#     shear_xyzr_N.txt            yade.export.text                       (#format x_y_z_r)
#     shear_attrs_N.txt           yade.export.textExt, format='x_y_z_r_attrs'
# The attributes in the last two: id (scalar), velocity (vector), displacement since the start
# (vector) and the number of intact cohesive bonds (scalar).
#
# BIG=1 yade -n -x shear_box.py: a block large enough to hold a shear band apart from its grips
# (40 x 8 x 24 mm, mean radius 0.5 mm, 6,310 spheres, frictionless walls on both y faces,
# 6 % shear in 4 snapshots), VTK files only: out/shearbig-spheres-0000000N.vtk, N = 0..3.

import os, time
from yade import pack, export
BIG = os.environ.get('BIG', '0') == '1'
t0 = time.time()

OUT = 'out'
os.makedirs(OUT, exist_ok=True)

# ---- geometry and materials ---------------------------------------------------------------
L, W, H = 0.030, 0.010, 0.016           # box in x, y, z (m)
RMEAN, FUZZ = 0.00075, 0.3
VSHEAR = 0.02                            # top grip speed (m/s)
SHEAR_STRAIN = 0.04                      # total shear displacement / H
NFRAMES = 3
if BIG:
    L, W, H = 0.040, 0.008, 0.024
    RMEAN = 0.0005
    SHEAR_STRAIN = 0.06
    NFRAMES = 4

grains = O.materials.append(CohFrictMat(
    young=1e8, poisson=0.3, density=2600, frictionAngle=radians(30),
    normalCohesion=1e6, shearCohesion=1e6, isCohesive=True,
    momentRotationLaw=True, etaRoll=0.1, alphaKr=2.0, alphaKtw=2.0, label='grains'))

sp = pack.randomDensePack(pack.inAlignedBox((0, 0, 0), (L, W, H)), radius=RMEAN, rRelFuzz=FUZZ,
                          spheresInCell=1500, returnSpherePack=True, seed=1)
sp.toSimulation(material=grains)
nSpheres = len(O.bodies)
print('packed %d spheres in %.0f s' % (nSpheres, time.time() - t0), flush=True)
if BIG:
    # frictionless walls on both y faces: the band is not pulled apart sideways
    wallMat = O.materials.append(CohFrictMat(young=1e8, poisson=0.3, density=2600, frictionAngle=0,
                                             isCohesive=False, momentRotationLaw=False))
    for yw in (0.0, W):
        a, b, c, d = (Vector3(-0.01, yw, -0.01), Vector3(L + 0.01, yw, -0.01),
                      Vector3(L + 0.01, yw, H + 0.01), Vector3(-0.01, yw, H + 0.01))
        O.bodies.append(facet([a, b, c], material=wallMat, fixed=True, wire=False))
        O.bodies.append(facet([a, c, d], material=wallMat, fixed=True, wire=False))

# grips: the bottom and top 2 mean diameters
bottom, top = [], []
for b in O.bodies:
    if not isinstance(b.shape, Sphere):
        continue
    z = b.state.pos[2]
    if z < 4 * RMEAN:
        bottom.append(b)
    elif z > H - 4 * RMEAN:
        top.append(b)
for b in bottom:
    b.state.blockedDOFs = 'xyzXYZ'
    b.state.vel = Vector3(0, 0, 0)
    b.shape.color = Vector3(0.3, 0.3, 0.8)
for b in top:
    b.state.blockedDOFs = 'xyzXYZ'
    b.state.vel = Vector3(VSHEAR, 0, 0)
    b.shape.color = Vector3(0.8, 0.3, 0.3)

# ---- engines --------------------------------------------------------------------------------
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.3, label='aabb'), Bo1_Facet_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom6D(interactionDetectionFactor=1.3, label='ig2'),
         Ig2_Facet_Sphere_ScGeom6D()],
        [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False)],
        [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True)],
    ),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, 0)),
]
O.dt = 0.5 * PWaveTimeStep()

# bonds are made on the first step between neighbours up to 30 % apart, then detection goes
# back to touching spheres only
O.step()
aabb.aabbEnlargeFactor = -1
ig2.interactionDetectionFactor = -1
for b in O.bodies:
    b.state.refPos = b.state.pos      # displacements count from here

nIter = int(SHEAR_STRAIN * H / VSHEAR / O.dt)
nPer = nIter // (NFRAMES - 1)

ATTRS = ['b.id', 'b.state.vel', 'b.state.displ()',
         'sum(1 for i in b.intrs() if i.isReal and not i.phys.cohesionBroken)']
vtk = export.VTKExporter(os.path.join(OUT, 'shearbig' if BIG else 'shear'))
spheres = [b.id for b in O.bodies if isinstance(b.shape, Sphere)]


def snapshot(n):
    t = O.time
    if BIG:
        vtk.exportSpheres(ids=spheres, what=dict(id='b.id'), numLabel=n)
        print('frame %d: iter %d t=%g s (%.0f s)' % (n, O.iter, t, time.time() - t0), flush=True)
        return
    vtk.exportSpheres(what=dict(id='b.id', velocity='b.state.vel', displacement='b.state.displ()',
                                nbonds=ATTRS[3]),
                      comment='Faultline shear_box.py t=%g s iter=%d' % (t, O.iter), numLabel=n)
    export.text(os.path.join(OUT, 'shear_xyzr_%d.txt' % n))
    export.textExt(os.path.join(OUT, 'shear_attrs_%d.txt' % n), format='x_y_z_r_attrs',
                   comment='id vx vy vz dx dy dz nbonds', attrs=ATTRS)
    bonds = sum(1 for i in O.interactions if i.isReal and not i.phys.cohesionBroken)
    print('frame %d: iter %d t=%g s, %d spheres, %d intact bonds' % (n, O.iter, t, nSpheres, bonds))


snapshot(0)                               # frame 0 at the start of shearing
for n in range(1, NFRAMES):
    O.run(nPer, True)
    snapshot(n)
print('done: %d spheres, %d steps of %g s' % (nSpheres, O.iter, O.dt))
