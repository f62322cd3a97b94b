// Scene description: what a user's scene.yaml asks mlshell to simulate.
//
// parse_scene() reads and validates the YAML file; it never touches PETSc, so it runs (and is
// tested) without MPI. Every error is a SceneError whose message names the file, the line, the key
// path (e.g. `effects[2].dirichlet.components`) and the offending value, and says what was
// expected.
//
// Units are SI throughout (m, kg, s, N, Pa); the denim preset converts the paper's Table 1 units.
#pragma once

#include <algorithm>
#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace mlshell {

/// Raised for any invalid scene: the message is complete and meant for the user as is.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Vec3 = std::array<double, 3>;

// ----------------------------------------------------------------------------------------------
// Geometry

/// `cage: {generator: rectangle, size: [w, h], faces: [nx, ny], origin: [x, y]}`
struct RectangleCage {
  std::array<double, 2> size{1.0, 1.0};
  std::array<int, 2> faces{4, 4};
  std::array<double, 2> origin{0.0, 0.0};
};

/// `cage: {generator: l-shape, size: [w, h], faces: [nx, ny], cut: [cx, cy], origin: [x, y]}`:
/// the rectangle minus its top-right cx × cy block (a re-entrant corner at (w-cx, h-cy)).
/// The cut must be a whole number of faces in each direction.
struct LShapeCage {
  std::array<double, 2> size{1.0, 1.0};
  std::array<int, 2> faces{10, 10};
  std::array<double, 2> cut{0.3, 0.3};
  std::array<double, 2> origin{0.0, 0.0};
};

/// `cage: {obj: path}` — a plain all-quad OBJ; path relative to the scene file's folder.
struct ObjCage {
  std::filesystem::path path;  ///< resolved (absolute or relative to the working directory)
};

/// `mesh: {obj: path}` or `mesh: {generator: rectangle | cylinder | dome | sphere, ...}`: a
/// triangle-mesh shell (paper 2) instead of a subdivision cage.
///   rectangle  size: [w, h], faces: [nx, ny] (structured; diagonals: alternating | uniform)
///              or edge_length: l (unstructured Delaunay), origin: [x, y]
///   cylinder   radius, length, faces: [around, along]   (axis z, two boundary loops),
///              imperfection: {amplitude, waves: [k, m], phase} or a list of them
///   dome       radius, opening_angle (rad, polar angle of the rim), rings   (apex on +z)
///   sphere     radius, subdivisions (icosphere: 20·4^s triangles, closed)
struct TriangleMeshSpec {
  enum class Generator { kObj, kRectangle, kCylinder, kDome, kSphere };
  Generator generator = Generator::kRectangle;
  std::filesystem::path obj;  ///< kObj: resolved path
  std::array<double, 2> size{1.0, 1.0};
  std::array<int, 2> faces{8, 8};
  std::optional<double> edge_length;  ///< rectangle: unstructured with this target edge length
  bool uniform_diagonals = false;     ///< structured rectangle: every diagonal from bottom-left
  std::array<double, 2> origin{0.0, 0.0};
  /// rectangle: an embossed rest shape, z = amplitude sin²(π nx u) sin²(π ny v) over the
  /// rectangle's (u, v) ∈ [0, 1]² — bumps[0] × bumps[1] bumps, flat along the boundary.
  double relief_amplitude = 0.0;
  std::array<int, 2> relief_bumps{1, 1};
  double radius = 1.0, length = 1.0, opening_angle = 1.0;
  /// cylinder: an imperfect wall, the radius r + Σ amplitude cos(k θ + phase) sin(m π z / length)
  /// over its modes, waves = [k around, m along]: round ends, and (with two modes or more, which
  /// leave no mirror symmetry) a buckling branch that the scene picks, not round-off.
  struct WallMode {
    double amplitude = 0.0;
    std::array<int, 2> waves{4, 1};
    double phase = 0.0;
  };
  std::vector<WallMode> imperfection;
  int rings = 8, subdivisions = 3;
};

/// `hierarchy: {levels: 4, ratio: 4}` or `{vertices: [2000, 500, 125]}`: coarser levels of a
/// triangle mesh by decimation (paper 2 §4.1). `vertices` lists the coarse levels' vertex counts,
/// finest-but-one first; otherwise each level has about 1/ratio of the next finer one's.
struct HierarchySpec {
  int levels = 4;              ///< in all, the fine mesh included: 2..12
  double ratio = 4.0;          ///< > 1
  std::vector<int> vertices;   ///< if given: strictly decreasing, ≥ 4 each
  /// How far a coarse boundary edge may stray from the fine boundary vertices it replaces, as a
  /// fraction of its length (DecimationOptions::boundary_deviation), in [0, 0.5).
  double boundary_deviation = 0.05;
};

struct GeometrySpec {
  std::variant<RectangleCage, LShapeCage, ObjCage> cage = RectangleCage{};
  int refine = 0;                        ///< uniform Catmull–Clark refinements of the cage, 0..8
  std::optional<TriangleMeshSpec> mesh;  ///< a triangle mesh instead of the cage
  std::optional<HierarchySpec> hierarchy;  ///< triangle meshes: decimated coarser levels
  bool triangles() const { return mesh.has_value(); }
  /// Named sides, corners and point(u, v) exist: a generated cage or triangle rectangle.
  bool has_frame() const;
};

// ----------------------------------------------------------------------------------------------
// Material

/// `{model: clyde-orthotropic, preset: denim, thickness, density, warp: [1,0,0]}` — eq.
/// (3.3)–(3.4). With a preset, k/d/mu/alpha come from the preset; any of k, mu, alpha may be given
/// explicitly instead (then all four phi_j must be given: `mu: [[...],[...],[...],[...]]`, same for
/// alpha).
/// Limit on the coupling term k2 φ2(Ẽ11 Ẽ22) relative to the Cauchy–Schwarz bound 2√(AB) of
/// the uncoupled energies A = k1/2 φ1(Ẽ11²), B = k3/2 φ3(Ẽ22²) (material.hpp): unchanged up to
/// `onset`·2√(AB), smoothly saturating towards `bound`·2√(AB), 0 < onset < bound < 1.
struct CouplingLimit {
  bool enabled = false;
  double onset = 0.75, bound = 0.9;
};

struct ClydeMaterial {
  std::array<double, 4> k{};                 ///< Pa (the paper's Table 1 gives MPa)
  std::array<std::vector<double>, 4> mu;     ///< mu_ji, i = 1..d_j
  std::array<std::vector<double>, 4> alpha;  ///< alpha_ji
  CouplingLimit coupling_limit;
};

/// `{model: isotropic-svk, youngs_modulus: E, poisson_ratio: nu, thickness, density}`
struct SvkMaterial {
  double youngs_modulus = 0.0;  ///< Pa, > 0
  double poisson_ratio = 0.0;   ///< in (-1, 0.5)
};

/// Triangle-mesh shells: `{model: neo-hookean | st-venant-kirchhoff, youngs_modulus: E,
/// poisson_ratio: nu, thickness, volume_density, bending: hinge | midedge}` — the membrane of
/// paper 2 (neo-Hookean, or St. Venant–Kirchhoff) plus discrete hinge bending (paper 2) or
/// midedge-normal bending; `volume_density` in kg/m³ (MaterialSpec's density is then
/// volume_density × thickness).
struct TriangleMaterial {
  bool neo_hookean = true;
  bool midedge_bending = false;  ///< `bending: midedge` (default: hinge)
  double youngs_modulus = 0.0;   ///< Pa, > 0
  double poisson_ratio = 0.0;    ///< in (-1, 0.5)
};

struct MaterialSpec {
  std::variant<ClydeMaterial, SvkMaterial, TriangleMaterial> model;
  std::string preset;        ///< "denim", "denim-table1" or empty
  double thickness = 0.0;    ///< m, > 0
  double density = 0.0;      ///< area density kg/m², >= 0
  Vec3 warp{1.0, 0.0, 0.0};  ///< projected onto the reference tangent plane: material direction o1
  int thickness_points = 3;  ///< Gauss points through the thickness, 1..8
};

/// Table 1 of the paper (denim), in SI units (k converted from MPa to Pa), with mu_j1 completed
/// so that sum_i mu_ji = 1 (phi_j'(0) = 1), and nothing else: preset `denim-table1`. Its energy
/// has a negative well (psi_min = -0.0205 MPa near E~ = (0.115, -0.11, 0); see material.hpp).
ClydeMaterial denim_table1_preset();
/// Preset `denim` (the default of the examples): Table 1 with the coupling limit
/// {onset 0.75, bound 0.9}, so that psi > 0 for every strain E~ != 0 while the uniaxial warp,
/// weft and shear responses and the small-strain tangent stay Table 1's.
ClydeMaterial denim_preset();

// ----------------------------------------------------------------------------------------------
// Selections: where an effect acts.

/// A boundary curve: all of it, a named side of a generated cage, or the boundary parts in a box.
/// On triangle meshes also one boundary loop (`boundary(loop k)`) or a named vertex group of the
/// OBJ file (`group(name)`); a box there selects every vertex inside it.
struct CurveSelection {
  enum class Kind { All, Side, Box, Loop, Group } kind = Kind::All;
  std::string side;  ///< Kind::Side: left|right|bottom|top (+ re-entrant for l-shape cages)
  Vec3 box_min{}, box_max{};
  int loop = 0;       ///< Kind::Loop
  std::string group;  ///< Kind::Group
};

/// A single point of the surface.
struct PointSelection {
  enum class Kind { At, Corner, Param } kind = Kind::At;
  Vec3 at{};                      ///< Kind::At: nearest point of the reference limit surface
  std::string corner;             ///< Kind::Corner: bottom-left|bottom-right|top-left|top-right
  std::array<double, 2> param{};  ///< Kind::Param: (u, v) in [0,1]² of a generated cage's domain
};

using Selection = std::variant<CurveSelection, PointSelection>;

/// Syntax (`where:` value): `boundary`, `boundary(left)`, `corner(top-right)`, `point(0.5, 0.5)`,
/// `{at: [x, y, z]}`, `{box: {min: [...], max: [...]}}`.
/// The string form is what the user wrote (kept for messages and summary.json).
struct Where {
  Selection selection;
  std::string text;
};

// ----------------------------------------------------------------------------------------------
// Effects: exactly the ones the scene lists are built.

/// `rotate: {axis: [ax, ay, az], center: [cx, cy, cz], angle: a}`: a rigid rotation by the
/// angle a (radians, right-handed about the axis) about the line through `center` along `axis`.
struct Rotation {
  Vec3 axis{0, 0, 1};    ///< any non-zero length
  Vec3 center{0, 0, 0};  ///< a point of the axis (m)
  double angle = 0.0;    ///< radians
};

/// 3×3 matrix, row-major: `m[i][j]`.
using Mat3 = std::array<Vec3, 3>;

/// A prescribed rigid motion (of `dirichlet` and `clamp` selections; written so that scripted
/// obstacles can take the same one):
///   `motion: {translate: [dx, dy, dz], rotate: {axis, center, angle}, over: [t0, t1]}`,
/// at least one of `translate` and `rotate`. With s(t) = clamp((t − t0)/(t1 − t0), 0, 1) the
/// point X of the reference is moved to
///   φ(X, t) = R(s θ) (X − c) + c + s T,
/// the rotation R by the angle s θ about the axis through c first, then the translation T; both
/// grow linearly from 0 at t0 to their full value at t1 and stay there (keyframes: a list of such
/// segments applied one after another is not supported; one segment per effect).
/// motion_function (effect_builder.hpp) turns it into the placements φ_t that the energy terms
/// apply (RigidPlacement, prescribed_motion.hpp).
struct Motion {
  Vec3 translate{0, 0, 0};
  std::array<double, 2> over{0.0, 0.0};  ///< t0 <= t1; t0 == t1 means a jump at t0
  std::optional<Rotation> rotate;
  /// s(t) ∈ [0, 1]: 0 up to t0, 1 from t1 on (a jump just after t0 when t0 == t1).
  double progress(double t) const;
  /// The translation s(t) T at time t.
  Vec3 at(double t) const;
  /// R(s(t) θ): the rotation by the angle reached at t about the unit axis (Rodrigues' formula
  /// R = I + sin α K + (1 − cos α) K², K the cross-product matrix of the unit axis); the
  /// identity without `rotate`.
  Mat3 rotation(double t) const;
  /// An upper bound of |φ(X, t) − X| over t for points X within `radius` of the rotation's
  /// centre: |T| + 2 radius |sin(θ/2)| (|θ| ≤ π), or |T| + 2 radius beyond a half turn.
  double reach(double radius) const;
};

struct InertiaEffect {};
struct GravityEffect {
  Vec3 acceleration{0, 0, -9.81};
};
struct SurfaceLoadEffect {
  Vec3 force_per_area{};
  bool ramp = false;
};
struct LineLoadEffect {
  Where where;
  Vec3 force_per_length{};
  bool ramp = false;
};
struct PointLoadEffect {
  Where where;
  Vec3 force{};
  bool ramp = false;
};

/// Penalty Dirichlet condition (paper eq. 3.6) with the scaled beta of penalty_parameter
/// (effect_builder.hpp; h^-sigma for the paper's denim) unless `penalty` is given.
/// `dirichlet: {where, components: [x, y, z], motion: {...}, sigma: 5, penalty: 1e8}`
struct DirichletEffect {
  Where where;
  std::array<bool, 3> components{true, true, true};
  std::optional<Motion> motion;
  double sigma = 5.0;             ///< > 0
  std::optional<double> penalty;  ///< explicit beta > 0 (overrides sigma)
  /// Augmented-Lagrangian mode: multipliers drive max |P(u − d)| below this (m, > 0).
  std::optional<double> tolerance;
};

/// Clamp: displacement and rotation (the slope across the boundary) held by penalties.
/// `clamp: {where, motion, sigma, penalty, rotation_penalty}`; `where` must be a curve.
struct ClampEffect {
  Where where;
  std::optional<Motion> motion;
  double sigma = 5.0;
  std::optional<double> penalty;
  std::optional<double> rotation_penalty;  ///< default beta * h^2
};

/// `pressure: {pressure: p, ramp: true}` — work p·(V(x) − V(X)) of the volume V enclosed by a
/// closed triangle-mesh surface (outward normals: p > 0 inflates).
struct PressureEffect {
  double pressure = 0.0;  ///< Pa
  bool ramp = false;
};

/// `contact: {thickness: ξ, gap: ĝ, self: true, stiffness: κ}` — IPC barrier contact of a
/// triangle shell with itself and with the scene's colliders (docs/contact.md): the
/// mid-surfaces keep a distance ξ, and the barrier acts within the gap ĝ beyond it.
struct ContactEffect {
  std::optional<double> thickness;  ///< ξ ≥ 0 (m); default the shell's thickness
  std::optional<double> gap;        ///< ĝ > 0 (m); default 10⁻³ × the shell's bounding-box diagonal
  bool self = true;                 ///< self-contact of the shell
  std::optional<double> stiffness;  ///< κ > 0, fixed; default adaptive (IPC)
};

/// An obstacle for contact (needs a `contact` effect), static or moved by `motion`:
/// `collider: {sphere: {center: [x, y, z], radius: r, subdivisions: 3}}`,
/// `collider: {plane: {point: [x, y, z], normal: [nx, ny, nz], size: s}}` (a square of side s),
/// `collider: {box: {center: [x, y, z], size: [sx, sy, sz]}}` or `collider: {obj: path}`.
struct ColliderEffect {
  enum class Shape { kSphere, kPlane, kBox, kObj } shape = Shape::kSphere;
  Vec3 center{0, 0, 0};            ///< sphere and box centre; the plane's point
  double radius = 0.0;             ///< sphere, > 0
  int subdivisions = 3;            ///< sphere: icosphere subdivisions, 0..6
  Vec3 normal{0, 0, 1};            ///< plane, non-zero (normalised)
  std::optional<double> side;      ///< plane: the square's side; default 4 shell diagonals
  Vec3 size{1, 1, 1};              ///< box edge lengths, > 0
  std::filesystem::path obj;       ///< obj: the resolved path of a triangle surface
  /// A scripted rigid motion of the whole collider (its points X go to φ(X, t)); none: static.
  std::optional<Motion> motion;
};

using Effect = std::variant<InertiaEffect, GravityEffect, SurfaceLoadEffect, LineLoadEffect,
                            PointLoadEffect, DirichletEffect, ClampEffect, PressureEffect,
                            ContactEffect, ColliderEffect>;

/// Name used in YAML, logs, CSV columns and summary.json ("inertia", "gravity", ...).
std::string effect_name(const Effect& e);

// ----------------------------------------------------------------------------------------------

/// `initial_state: {affine: [[3x3]], translate: [x,y,z]}` or `initial_state: {checkpoint: path}`.
struct InitialState {
  std::optional<std::array<Vec3, 3>> affine;  ///< x0 = A X + translate
  Vec3 translate{0, 0, 0};
  std::optional<std::filesystem::path> checkpoint;  ///< resolved path
};

/// `time.preview`: Algorithm 1 of paper 2 (§4.5), the proxy steps of a progressive run's coarse
/// levels. A proxy step takes at most `max_iterations` Newton iterations with a line search on the
/// level's proxy energy, and stops early when ‖d‖₂ < √n_l ε ℓ (n_l the level's vertices, ℓ the
/// finest mean edge length: the paper's √n_l h ε with the length h ε made relative to the mesh)
/// or when the line search needs α < γ. A level is in equilibrium when a proxy step stops
/// before its first iteration; it gives up after `max_steps` proxy steps past the loading.
struct PreviewSpec {
  int max_iterations = 5;  ///< max_iter, 1..1000
  double tolerance = 1e-3;  ///< ε, > 0 (relative to the finest mean edge length)
  double min_step = 1e-3;   ///< γ, in (0, 1)
  int max_steps = 200;      ///< proxy steps per level after the loading, 1..1000000
};

/// `time: {dt, steps, integrator, proximal_step, max_proximal_solves, preview}`.
struct TimeSpec {
  enum class Integrator { kImplicitEuler, kQuasistatic, kProgressive };
  double dt = 1.0;  ///< > 0
  int steps = 1;    ///< >= 1
  /// implicit_euler (paper 1, with the scene's inertia effect) or quasistatic (paper 2 eq. 1:
  /// each step is a sequence of proximal solves; `dt` is the load step of moving boundary
  /// conditions and ramps)
  Integrator integrator = Integrator::kImplicitEuler;
  double proximal_step = 1.0;  ///< quasistatic: the artificial step h (s) of ½h⁻²‖x − xᵗ‖²_M
  int max_proximal_solves = 50;  ///< quasistatic: proximal solves per step before giving up
  /// progressive (paper 2 §3, Alg. 1): the loading as proxy steps on the coarsest level of
  /// geometry.hierarchy, refined level by level to the finest, solved there as quasistatic.
  PreviewSpec preview;
  /// Quasistatic stepping, on the finest level alone or progressively.
  bool quasistatic() const { return integrator != Integrator::kImplicitEuler; }
  bool progressive() const { return integrator == Integrator::kProgressive; }
};

struct Probe {
  std::string name;
  Where where;  ///< must be a point selection
};

struct OutputSpec {
  std::filesystem::path dir = "out";  ///< resolved relative to the working directory
  int every = 1;                      ///< write frames every N steps (the last step always)
  std::vector<std::string> formats{"xdmf", "obj", "csv"};  ///< subset of xdmf|obj|csv
  /// Limit-surface grid per face and direction for xdmf/obj, 1..16; 0 (the default): as many
  /// as resolve the surface at the scene's refinement (samples_for).
  int samples_per_face = 0;
  /// The grid at refinement `refine`: samples_per_face if given, else 4 up to refine 2, 2 at
  /// refine 3 and 1 beyond (about 16 samples per cage-face edge, at most 4 per face): a face
  /// of a fine level is nearly flat, and a frame keeps a few points per control point instead
  /// of 16 (135 MB of OBJ text per frame at 201,243 dofs with 4, each element's 25 apart).
  int samples_for(int refine) const {
    return samples_per_face > 0 ? samples_per_face : std::clamp(16 >> std::min(refine, 4), 1, 4);
  }
  int checkpoint_every = 0;  ///< 0: no checkpoints
};

/// `solver: {options_file: path}` — PETSc options are the main knob (tolerances included).
struct SolverSpec {
  std::optional<std::filesystem::path> options_file;  ///< resolved path; command line wins
};

/// `bodies: [{name, mesh, translate, material, self_contact}]`: a further triangle-mesh shell
/// beside geometry.mesh, with its own mesh, placement and material (the scene's by default). Its
/// vertices are group(name), its mesh's own groups group(name/group). All bodies form one
/// discretization; effects act on all of them unless a selection picks some.
struct BodySpec {
  std::string name;
  TriangleMeshSpec mesh;
  Vec3 translate{0.0, 0.0, 0.0};
  MaterialSpec material;
  std::optional<bool> self_contact;  ///< default: the contact effect's `self`
};

struct Scene {
  std::filesystem::path file;  ///< the scene file as given
  std::string name;            ///< file stem unless `name:` is given
  GeometrySpec geometry;
  MaterialSpec material;
  std::vector<BodySpec> bodies;  ///< further shells (triangle meshes), in the file's order
  std::vector<Effect> effects;
  InitialState initial_state;
  TimeSpec time;
  std::vector<Probe> probes;
  OutputSpec output;
  SolverSpec solver;

  bool has_inertia() const;
};

/// Reads and validates a scene file. Throws SceneError (see the header comment).
Scene parse_scene(const std::filesystem::path& file);

/// Parses a `where:` string form (`boundary(left)`, `corner(top-left)`, `point(0.5,0.5)`,
/// `boundary`). Throws SceneError with `context` (file:line: key) prefixed to the message.
Where parse_where_text(const std::string& text, const std::string& context);

/// The scene format, for `mlshell --help`.
const char* scene_format_help();

}  // namespace mlshell
