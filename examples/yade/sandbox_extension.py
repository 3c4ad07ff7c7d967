# Faultline example: a bonded (cohesive) sandbox stretched over a
# basal velocity discontinuity (Yade). About 5,850 spheres (mean radius 0.5 mm +-20 %) fill a
# 60 x 6 x 20 mm box (pack.randomDensePack, seed 3); neighbours are bonded on the first step
# (CohFrictMat, E 1 MPa, bond strength COH Pa, default 2000), frictionless facet walls hold the
# two y faces, gravity acts. The bottom two radii and both end walls of grains are frozen; the
# right half of the base and the right wall then move +x by 4 mm at 1 cm/s: the block above the
# edge of the fixed half (x = 30 mm) stretches and normal faults grow from it.
#
# Run from this folder (batch mode, no GUI; one thread, 10 minutes on the project's machine):
#     yade -n -x sandbox_extension.py            (COH=1500 yade -n -x ... for weaker bonds)
#     FLOOR=1 yade -n -x sandbox_extension.py    (a frictional floor under the base: the grains
#                                                 over the opening gap stay in; out/sbfloor-*)
# Output: out/sb-spheres-0000000N.vtk, N = 0..4 (VTKExporter: id, radius), frame 0 after 0.05 s
# of settling under gravity, then one frame per millimetre of pull.
import os, time
from yade import pack, export
OUT = 'out'; os.makedirs(OUT, exist_ok=True)
L, W, H = 0.060, 0.006, 0.020
RMEAN, FUZZ = 0.0005, 0.2
C = float(os.environ.get('COH', '2000'))       # bond strength, Pa
FLOOR = os.environ.get('FLOOR', '0') == '1'   # a floor under the base (output prefix sbfloor)
V = 0.01; PULL = 0.004; NFRAMES = 5
mat = O.materials.append(CohFrictMat(young=1e6, poisson=0.3, density=2600, frictionAngle=radians(30),
      normalCohesion=C, shearCohesion=C, isCohesive=True, momentRotationLaw=True, etaRoll=0.1,
      alphaKr=2.0, alphaKtw=2.0))
t0 = time.time()
sp = pack.randomDensePack(pack.inAlignedBox((0, 0, 0), (L, W, H)), radius=RMEAN, rRelFuzz=FUZZ,
                          spheresInCell=2000, returnSpherePack=True, seed=3)
sp.toSimulation(material=mat)
print('packed %d spheres in %.0f s' % (len(O.bodies), time.time() - t0))
wallMat = O.materials.append(CohFrictMat(young=1e6, poisson=0.3, density=2600, frictionAngle=0,
      isCohesive=False, momentRotationLaw=False))
if FLOOR:
    # A frictional floor under the base: where the moving half pulls away from the fixed one,
    # the grains above the gap settle on it instead of pouring out of the model.
    floorMat = O.materials.append(CohFrictMat(young=1e6, poisson=0.3, density=2600,
          frictionAngle=radians(30), isCohesive=False, momentRotationLaw=False))
    fa, fb, fc, fd = Vector3(-0.01, -0.01, 0), Vector3(L + 0.01, -0.01, 0), Vector3(L + 0.01, W + 0.01, 0), Vector3(-0.01, W + 0.01, 0)
    O.bodies.append(facet([fa, fb, fc], material=floorMat, fixed=True, wire=False))
    O.bodies.append(facet([fa, fc, fd], material=floorMat, fixed=True, wire=False))
for yw in (0.0, W):
    a, b, c, d = Vector3(-0.01, yw, -0.01), Vector3(L + 0.01, yw, -0.01), Vector3(L + 0.01, yw, H + 0.01), Vector3(-0.01, yw, H + 0.01)
    O.bodies.append(facet([a, b, c], material=wallMat, fixed=True, wire=False))
    O.bodies.append(facet([a, c, d], material=wallMat, fixed=True, wire=False))
movers, fixed = [], []
for b in O.bodies:
    if not isinstance(b.shape, Sphere):
        continue
    x, z = b.state.pos[0], b.state.pos[2]
    if z < 2 * RMEAN or x < 2 * RMEAN or x > L - 2 * RMEAN:
        b.state.blockedDOFs = 'xyzXYZ'
        b.state.vel = Vector3(0, 0, 0)
        if (z < 2 * RMEAN and x >= L / 2) or x > L - 2 * RMEAN:
            movers.append(b)
        else:
            fixed.append(b)
O.engines = [ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.3, label='aabb'), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D(interactionDetectionFactor=1.3, label='ig2'), Ig2_Facet_Sphere_ScGeom6D()],
        [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False)],
        [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True)]),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81))]
O.dt = 0.5 * PWaveTimeStep()
O.step(); aabb.aabbEnlargeFactor = -1; ig2.interactionDetectionFactor = -1
O.run(int(0.05 / O.dt), True)   # settle under gravity 0.05 s
vtk = export.VTKExporter(os.path.join(OUT, 'sbfloor' if FLOOR else 'sb'))
def snap(n):
    vtk.exportSpheres(ids=[b.id for b in O.bodies if isinstance(b.shape, Sphere)], what=dict(id='b.id'), numLabel=n)
    bonds = sum(1 for i in O.interactions if i.isReal and not i.phys.cohesionBroken)
    print('frame %d iter %d bonds %d (%.0f s)' % (n, O.iter, bonds, time.time() - t0), flush=True)
snap(0)
for b in movers: b.state.vel = Vector3(V, 0, 0)
per = int(PULL / V / O.dt / (NFRAMES - 1))
for n in range(1, NFRAMES):
    O.run(per, True); snap(n)
print('dt %g, steps %d' % (O.dt, O.iter))
