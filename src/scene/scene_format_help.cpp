// The scene-file reference printed by `mlshell --help`. Keep it in step with the readers in this
// folder: scene_test.cpp checks that its example parses and that it names every key.
#include "mlshell/scene.hpp"

namespace mlshell {

const char* scene_format_help() {
  return R"(SCENE FILE FORMAT (YAML)
Units are SI: m, kg, s, N, Pa. Unknown keys, wrong types and out-of-range values are errors that
name the file, line, key and value. Relative paths in obj, checkpoint and options_file are taken
from the scene file's folder; output.dir from the current directory. NaN and Inf are never valid.

name: string                 optional; default: the scene file's name without extension
geometry:                    required
  cage:                      required; one of
    {generator: rectangle, size: [w, h], faces: [nx, ny], origin: [x, y]}
        size > 0 (default [1, 1]); faces >= 1 (default [4, 4]); origin default [0, 0]
    {generator: l-shape, size: [w, h], faces: [nx, ny], cut: [cx, cy], origin: [x, y]}
        the rectangle minus its top-right cx x cy block; defaults size [1, 1], faces [10, 10],
        cut [0.3, 0.3]; each cut in (0, size), a whole number of faces, one face left at least
    {obj: path}              an all-quad OBJ mesh
  refine: int                uniform Catmull-Clark refinements of the cage, 0..8 (default 0)
  mesh:                      instead of cage and refine: a triangle-mesh shell (paper 2); one of
    {obj: path}              a triangle OBJ; `g name` lines name vertex groups for group(name)
    {generator: rectangle, size: [w, h], faces: [nx, ny], origin: [x, y], diagonals: d}
        structured, defaults size [1, 1], faces [8, 8], d alternating (or uniform); or
        edge_length: l      an unstructured Delaunay mesh with edges of about l (<= w/2, h/2)
        relief: {amplitude: a, bumps: [bx, by]}   embossed: z = a sin^2(pi bx u) sin^2(pi by v)
    {generator: cylinder, radius: r, length: l, faces: [around >= 3, along]}   open, axis z
        imperfection: {amplitude: a, waves: [k, m], phase: p} or a list: radius r + the sum
                      of a cos(k theta + p) sin(m pi z/l); two modes leave no mirror symmetry
    {generator: dome, radius: r, opening_angle: a, rings: n}   apex on +z, rim at a in (0, pi)
    {generator: sphere, radius: r, subdivisions: s}   closed icosphere, s in 0..8
  hierarchy:                 triangle meshes, for -tao_type rmtr: coarser levels by edge collapse
    {levels: n, ratio: r, boundary_deviation: d}   levels 2..12 (4), each 1/r of the finer
                             one's vertices (r 4), or {vertices: [n1, ...]}; d: 0.05 per length
material:                    required
  model: clyde-orthotropic   woven cloth, eq. (3.3)-(3.4) of Kopanicakova et al. 2019
    preset: denim            Table 1 of the paper with its coupling limited so that the energy is
                             positive for every strain (the default of the examples)
    preset: denim-table1     Table 1 as printed: a negative energy well near E~ = (0.115, -0.11,
                             0) that free cloth falls into (k, mu, alpha below override presets)
    coupling_limit: none | {onset: a, bound: b}   0 < a < b < 1: k2 phi2(E11 E22) kept below
                             a 2 sqrt(AB), saturating to b 2 sqrt(AB) (denim: 0.75, 0.9)
    k: [k1, k2, k3, k4]      Pa, each > 0 (required without a preset)
    mu: [[...], x4]          mu_ji, four non-empty lists (required without a preset)
    alpha: [[...], x4]       alpha_ji, nonzero, same lengths as mu (required without a preset)
    warp: [x, y, z]          warp direction, nonzero (default [1, 0, 0])
  model: isotropic-svk       St. Venant-Kirchhoff
    youngs_modulus: E        Pa, > 0 (required)
    poisson_ratio: nu        in (-1, 0.5) (required)
  model: neo-hookean | st-venant-kirchhoff   triangle meshes (E, nu, thickness as above):
    volume_density: number   kg/m^3, >= 0 (required; instead of density)
    bending: hinge | midedge hinge (default, paper 2) or midedge (Kirchhoff plate; docs/physics.md)
  thickness: number          m, > 0; required (denim preset: 0.66e-3)
  density: number            area density kg/m^2, >= 0; required (denim preset: 0.4)
  thickness_points: int      Gauss points through the thickness, 1..8 (default 3)
bodies:                      triangle meshes: a list of further shells, each
  name: string               group(name) selects it, group(name/left) its mesh's sides, ...
  mesh: {...}, translate: [x, y, z]   as geometry.mesh, moved into place
  material: {...}            the scene's unless given (the same bending model)
  self_contact: bool         its contact with itself (default: contact's self)
effects:                     optional list of names or {name: params}; only those are simulated
  - inertia                  implicit Euler inertia; at most once
  - gravity: [gx, gy, gz]    m/s^2; bare `- gravity` means [0, 0, -9.81]; at most once
  - surface_load: {force_per_area: [fx, fy, fz], ramp: bool}            N/m^2
  - line_load: {where: CURVE, force_per_length: [fx, fy, fz], ramp: bool} N/m
  - point_load: {where: POINT, force: [fx, fy, fz], ramp: bool}          N
  - dirichlet: {where: CURVE or POINT, components: [x, y, z], motion: MOTION, sigma: s,
                penalty: beta, tolerance: t}   t (m, > 0): augmented Lagrangian to |u - d| <= t
  - clamp: {where: CURVE, motion: MOTION, sigma: s, penalty: beta, rotation_penalty: b}
  - pressure: {pressure: p, ramp: bool}   Pa; work p (V(x) - V(X)) of a closed triangle mesh's
                             volume (outward normals: p > 0 inflates; open or inward: refused)
  - contact: {thickness: t, gap: g, self: bool, stiffness: k}   triangle meshes: IPC barrier,
                             at most once (docs/contact.md; defaults: the shell's, 1e-3 L, true)
  - collider: {sphere: {center: c, radius: r, subdivisions: n}, plane: {point: p, normal: n,
               side: s}, box: {center: c, size: [sx, sy, sz]}, obj: path, motion: MOTION}
    ramp: false (default) or true: the load grows linearly from 0 to full over the steps.
    components: non-empty subset of x, y, z, no repeats (default all three).
    sigma: > 0 (default 5): penalty beta = (Y tau / Y tau_denim) (1 m / L) (h / L)^-sigma for the
        finest mesh size h, the membrane stiffness Y tau of the material and the size L of the
        surface (the paper's h^-sigma for its 1 m denim); penalty: explicit beta > 0.
    rotation_penalty: > 0 (default beta * h^2; triangle meshes: the clamp's k or D, default the
        shell's own bending stiffness).
    MOTION = {translate: [dx, dy, dz], rotate: {axis: [ax, ay, az], center: [cx, cy, cz],
    angle: a}, over: [t0, t1]}, translate or rotate or both: X moves to R(s a)(X - center) +
    center + s translate (a in radians, right-handed); s: 0 until t0, linear to 1 at t1 >= t0.
initial_state:               optional; default: the reference configuration
  affine: [[a11, a12, a13], [a21, a22, a23], [a31, a32, a33]]      x0 = A X + translate
  translate: [x, y, z]       m (default [0, 0, 0])
  checkpoint: path           restart from a checkpoint (alone: not with affine or translate)
time:                        required
  dt: number                 s, > 0
  steps: int                 1..1000000
  integrator: implicit_euler | quasistatic | progressive   default implicit_euler; quasistatic:
                             argmin |x - x_k|_M^2/(2 h^2) + E(x) until |grad E| is small (paper 2
                             eq. 1); progressive: coarsest level of geometry.hierarchy to finest
  proximal_step: h           s, > 0 (default 1), max_proximal_solves: int per step (default 50)
  preview: {max_iterations: 5, tolerance: 1e-3, min_step: 1e-3, max_steps: 200}   (progressive)
probes:                      optional map NAME: POINT; NAME uses letters, digits, _ - .
output:                      optional
  dir: path                  default out
  every: int                 write frames every N steps, >= 1 (default 1; the last step always)
  formats: [xdmf, obj, csv]  subset without repeats (default all three)
  samples_per_face: int      limit-surface samples per face and direction, 1..16 (default:
                             4 up to refine 2, 2 at refine 3, 1 beyond)
  checkpoint_every: int      steps between checkpoints, >= 0 (default 0: none)
solver:                      optional
  options_file: path         default PETSc options; -options_file replaces them (--help above)

WHERE: selections for effects and probes
  CURVE  boundary                 the whole boundary
         boundary(SIDE)           SIDE: left, right, bottom, top; re-entrant (l-shape cages only)
         {box: {min: [x, y, z], max: [x, y, z]}}     boundary parts inside the box; min <= max
                                  (on triangle meshes: every vertex inside the box)
         boundary(loop k), group(name)   triangle meshes: boundary loop k = 0, 1, ..., the
                                  vertices of an OBJ group (rectangles: left, right, bottom, top)
  POINT  {at: [x, y, z]}          the surface point nearest to (x, y, z)
         corner(CORNER)           CORNER: bottom-left, bottom-right, top-left, top-right (not on
                                  an l-shape, whose top-right block is cut away)
         point(u, v)              u, v in [0, 1] over the cage's rectangle, outside the cut
  Named sides, corners and point(u, v) need a generated cage or rectangle mesh; else use
  {at: ...} or {box: ...}. On triangle meshes a POINT is the nearest vertex. Inside a {...}
  map, quote point(u, v): the comma would end the value otherwise.

EXAMPLE (examples/drape.yaml, the main job; docs/scene-format.md has every key in detail)
  geometry:
    cage: {generator: rectangle, size: [1.0, 1.0], faces: [4, 4]}
    refine: 2                    # 1,083 dofs
  material: {model: clyde-orthotropic, preset: denim, thickness: 0.66e-3, density: 0.4}
  effects:
    - inertia
    - gravity: [0, 0, -9.81]
    - dirichlet:
        where: corner(bottom-left)
        motion: {translate: [0.141421356, 0.141421356, 0], over: [0, 10]}
    - dirichlet:
        where: corner(top-right)
        motion: {translate: [-0.141421356, -0.141421356, 0], over: [0, 10]}
  time: {dt: 1.0, steps: 10}
  probes:
    center: {at: [0.5, 0.5, 0]}
    bottom-right: {at: [1.0, 0.0, 0]}
  output: {dir: out/drape, every: 1, formats: [xdmf, obj, csv], checkpoint_every: 5}
)";
}

}  // namespace mlshell
