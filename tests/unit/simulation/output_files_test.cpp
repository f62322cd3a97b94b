// Tests of the result-file writers (include/mlshell/output_files.hpp): atomic writes, OBJ,
// XDMF+HDF5 (read back through PETSc's HDF5 viewer), CSV, JSON and binary checkpoints.
#include "mlshell/output_files.hpp"

#include <gtest/gtest.h>
#include <petscis.h>
#include <petscvec.h>
#include <petscviewer.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hdf5_readback.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/simulation.hpp"

namespace fs = std::filesystem;
using mlshell::OutputError;
using mlshell_test::load_is;
using mlshell_test::load_vec;

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_raw(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Lists leftover `*.tmp.*` files anywhere below `dir`.
std::vector<std::string> temporaries_under(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos)
      found.push_back(e.path().string());
  return found;
}

// A 2×1 strip of quads (6 points), with coordinates that do not print exactly in decimal.
mlshell::SurfaceSample strip(double shift) {
  mlshell::SurfaceSample s;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      s.points.push_back(0.1 * i + shift);
      s.points.push_back(j / 3.0);
      s.points.push_back(std::sin(i + j + shift) * 1e-7);
    }
  s.cells = {0, 1, 4, 3, 1, 2, 5, 4};
  for (std::size_t k = 0; k < s.points.size(); ++k) s.displacement.push_back(shift * k - 1.0 / 7);
  return s;
}

// Minimal well-formedness check: every element closes in order, only one root.
bool xml_balanced(const std::string& x) {
  std::vector<std::string> stack;
  int roots = 0;
  for (std::size_t i = x.find('<'); i != std::string::npos; i = x.find('<', i + 1)) {
    const std::size_t end = x.find('>', i);
    if (end == std::string::npos) return false;
    const std::string tag = x.substr(i + 1, end - i - 1);
    if (tag.empty()) return false;
    if (tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      if (stack.empty() || stack.back() != tag.substr(1)) return false;
      stack.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
    if (stack.empty()) ++roots;
    if (tag.back() != '/') stack.push_back(name);
  }
  return stack.empty() && roots == 1;
}

int count(const std::string& haystack, const std::string& needle) {
  int n = 0;
  for (auto p = haystack.find(needle); p != std::string::npos; p = haystack.find(needle, p + 1))
    ++n;
  return n;
}

class OutputFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("mlshell_output_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

// Runs `f`, expects OutputError, and returns its message.
template <class F>
std::string output_error_of(F&& f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no OutputError thrown";
  return {};
}

// --- atomic writes ----------------------------------------------------------------------------

TEST_F(OutputFiles, AtomicWriteCreatesFoldersAndReplacesContent) {
  const fs::path p = dir_ / "a" / "b" / "out.txt";
  mlshell::write_file_atomic(p, "first version, rather long\n");
  EXPECT_EQ(read_text(p), "first version, rather long\n");
  mlshell::write_file_atomic(p, "second");
  EXPECT_EQ(read_text(p), "second");
  mlshell::write_file_atomic(p, "");
  EXPECT_TRUE(fs::exists(p));
  EXPECT_EQ(fs::file_size(p), 0u);
  EXPECT_TRUE(temporaries_under(dir_).empty());
}

TEST_F(OutputFiles, AtomicWriteUnderARegularFileThrowsNamingThePath) {
  write_raw(dir_ / "plain", "x");
  const fs::path p = dir_ / "plain" / "sub" / "out.txt";
  const std::string msg = output_error_of([&] { mlshell::write_file_atomic(p, "data"); });
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_TRUE(temporaries_under(dir_).empty());
}

TEST_F(OutputFiles, AtomicWriteOverAFolderThrowsAndRemovesTheTemporary) {
  const fs::path p = dir_ / "occupied";
  fs::create_directories(p / "inside");
  const std::string msg = output_error_of([&] { mlshell::write_file_atomic(p, "data"); });
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_TRUE(fs::is_directory(p));
  EXPECT_TRUE(temporaries_under(dir_).empty());
}

TEST_F(OutputFiles, AtomicWriteFailingMidwayThrowsAndKeepsTheOldFile) {
  // A file-size limit makes write() fail part-way (EFBIG), standing in for a full disk.
  const fs::path p = dir_ / "big.txt";
  mlshell::write_file_atomic(p, "old");
  struct rlimit saved {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  if (saved.rlim_cur != RLIM_INFINITY && saved.rlim_cur < 4096) GTEST_SKIP();
  auto* old_handler = std::signal(SIGXFSZ, SIG_IGN);  // else the kernel kills the process
  struct rlimit small = saved;
  small.rlim_cur = 1024;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string msg;
  try {
    mlshell::write_file_atomic(p, std::string(100000, 'x'));
  } catch (const OutputError& e) {
    msg = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find(std::strerror(EFBIG)), std::string::npos) << msg;
  EXPECT_EQ(read_text(p), "old");
  EXPECT_TRUE(temporaries_under(dir_).empty());
}

// --- OBJ --------------------------------------------------------------------------------------

TEST_F(OutputFiles, ObjRoundTrip) {
  const auto s = strip(0.3);
  const fs::path p = dir_ / "surface.obj";
  mlshell::write_obj(p, s, "mlshell test\nsecond line");
  std::istringstream in(read_text(p));
  std::vector<double> pts;
  std::vector<std::int64_t> quads;
  int comments = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string kind;
    ls >> kind;
    if (kind == "#") {
      ++comments;
    } else if (kind == "v") {
      std::string x;
      for (int k = 0; k < 3; ++k) {
        ls >> x;
        pts.push_back(std::strtod(x.c_str(), nullptr));
      }
    } else if (kind == "f") {
      std::int64_t a;
      for (int k = 0; k < 4; ++k) {
        ls >> a;
        quads.push_back(a - 1);
      }
      EXPECT_FALSE(ls >> a) << "more than 4 indices: " << line;
    } else {
      ADD_FAILURE() << "unexpected line: " << line;
    }
  }
  EXPECT_GE(comments, 2);
  EXPECT_EQ(pts, s.points);  // bit-exact: the shortest text that reads back exactly
  EXPECT_EQ(quads, s.cells);
  EXPECT_NE(read_text(p).find("# mlshell test\n# second line\n"), std::string::npos);
}

TEST_F(OutputFiles, ObjRejectsOutOfRangeIndices) {
  auto s = strip(0.0);
  s.cells[3] = 6;
  EXPECT_THROW(mlshell::write_obj(dir_ / "bad.obj", s, ""), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "bad.obj"));
}

// --- XDMF + HDF5 ------------------------------------------------------------------------------

TEST_F(OutputFiles, XdmfSeriesWritesFramesReadableBack) {
  const fs::path out = dir_ / "results";
  mlshell::XdmfSeries series(out, "shell");
  EXPECT_EQ(series.xdmf_path(), out / "shell.xdmf");
  const auto s0 = strip(0.0), s1 = strip(0.25);
  series.add_frame(0, 0.0, s0);
  const std::string after_one = read_text(series.xdmf_path());
  EXPECT_TRUE(xml_balanced(after_one)) << after_one;
  EXPECT_EQ(count(after_one, "<Time "), 1);
  series.add_frame(10, 0.1, s1);

  const std::string x = read_text(series.xdmf_path());
  EXPECT_TRUE(xml_balanced(x)) << x;
  EXPECT_NE(x.find("<Xdmf Version=\"3.0\">"), std::string::npos);
  EXPECT_NE(x.find("GridType=\"Collection\" CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_EQ(count(x, "GridType=\"Uniform\""), 2);
  EXPECT_NE(x.find("<Time Value=\"0\"/>"), std::string::npos) << x;
  EXPECT_NE(x.find("<Time Value=\"0.1\"/>"), std::string::npos) << x;
  EXPECT_EQ(count(x, "TopologyType=\"Quadrilateral\" NumberOfElements=\"2\""), 2);
  EXPECT_EQ(count(x, "GeometryType=\"XYZ\""), 2);
  EXPECT_EQ(count(x, "<Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">"),
            2);
  const std::string int_item = "Dimensions=\"2 4\" NumberType=\"Int\" Precision=\"" +
                               std::to_string(sizeof(PetscInt)) + "\" Format=\"HDF\">";
  EXPECT_NE(x.find(int_item + "shell_000000.h5:/topology<"), std::string::npos) << x;
  EXPECT_NE(x.find(int_item + "shell_000010.h5:/topology<"), std::string::npos) << x;
  const std::string dbl_item =
      "Dimensions=\"6 3\" NumberType=\"Float\" Precision=\"8\" "
      "Format=\"HDF\">shell_000010.h5:/";
  EXPECT_NE(x.find(dbl_item + "geometry<"), std::string::npos) << x;
  EXPECT_NE(x.find(dbl_item + "displacement<"), std::string::npos) << x;

  for (const auto& [file, s] :
       {std::pair{"shell_000000.h5", s0}, std::pair{"shell_000010.h5", s1}}) {
    const fs::path h5 = out / file;
    ASSERT_TRUE(fs::exists(h5)) << h5;
    PetscInt bs = 0;
    EXPECT_EQ(load_vec(h5, "geometry", &bs), s.points);
    EXPECT_EQ(bs, 3);  // stored as N×3
    EXPECT_EQ(load_vec(h5, "displacement", &bs), s.displacement);
    EXPECT_EQ(bs, 3);
    EXPECT_EQ(load_is(h5, "topology", &bs), s.cells);
    EXPECT_EQ(bs, 4);  // stored as M×4
  }
  EXPECT_TRUE(temporaries_under(dir_).empty());
}

/// The vertex positions of an OBJ file, 3 per vertex.
std::vector<double> obj_vertices(const fs::path& p) {
  std::ifstream in(p);
  std::vector<double> out;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("v ", 0) == 0) {
      std::istringstream ss(line.substr(2));
      double x, y, z;
      ss >> x >> y >> z;
      out.insert(out.end(), {x, y, z});
    }
  return out;
}

TEST_F(OutputFiles, SimulationFramesHoldEachStepsState) {
  // The clamped plate under a ramped load (half at step 1, all at step 2): every frame's HDF5
  // geometry is the deformed surface of that step, the OBJ of the same frame has the same
  // vertices, and geometry − displacement is the rest surface (frame 0, zero displacement).
  mlshell::Scene scene = mlshell::parse_scene(fs::path(MLSHELL_SOURCE_DIR) / "examples/plate.yaml");
  scene.geometry.refine = 1;
  scene.time.steps = 2;
  for (auto& e : scene.effects)
    if (auto* load = std::get_if<mlshell::SurfaceLoadEffect>(&e)) load->ramp = true;
  scene.output.dir = dir_ / "run";
  scene.output.formats = {"xdmf", "obj"};
  scene.output.samples_per_face = 2;
  scene.output.checkpoint_every = 0;
  mlshell::SimulationOptions options;
  options.quiet = true;
  int status = -1;
  {
    mlshell::Simulation sim(PETSC_COMM_SELF, scene, options);
    ASSERT_EQ(sim.run(&status), 0);
  }
  ASSERT_EQ(status, 0);
  std::vector<double> reference, previous;
  for (int k = 0; k <= 2; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "%s_%06d.h5", scene.name.c_str(), k);
    PetscInt bs = 0;
    const std::vector<double> geometry = load_vec(scene.output.dir / name, "geometry", &bs);
    const std::vector<double> u = load_vec(scene.output.dir / name, "displacement", &bs);
    std::snprintf(name, sizeof name, "frame_%06d.obj", k);
    const std::vector<double> obj = obj_vertices(scene.output.dir / name);
    ASSERT_EQ(obj.size(), geometry.size()) << "frame " << k;
    ASSERT_EQ(u.size(), geometry.size()) << "frame " << k;
    if (k == 0) reference = geometry;
    double moved = 0.0, rest = 0.0, same = 0.0;
    for (size_t i = 0; i < u.size(); ++i) {
      moved = std::max(moved, std::abs(u[i]));
      rest = std::max(rest, std::abs(geometry[i] - u[i] - reference[i]));
      same = std::max(same, std::abs(geometry[i] - obj[i]));
    }
    EXPECT_LT(rest, 1e-12) << "frame " << k << ": geometry - displacement is not the rest surface";
    EXPECT_LT(same, 1e-12) << "frame " << k << ": the OBJ and the HDF5 geometry differ";
    if (k == 0) EXPECT_EQ(moved, 0.0) << "the initial frame is the rest state";
    if (k > 0) {
      EXPECT_GT(moved, 1e-8) << "frame " << k << " shows no displacement";
      double change = 0.0;
      for (size_t i = 0; i < u.size(); ++i) change = std::max(change, std::abs(u[i] - previous[i]));
      EXPECT_GT(change, 1e-3 * moved) << "frame " << k << " repeats the previous frame";
    }
    previous = u;
  }
}

TEST_F(OutputFiles, XdmfSeriesWithoutDisplacementAndRepeatedStep) {
  mlshell::XdmfSeries series(dir_, "bare");
  auto s = strip(0.5);
  s.displacement.clear();
  series.add_frame(3, 1.5, s);
  series.add_frame(3, 2.5, s);  // a repeated step replaces the entry
  const std::string x = read_text(series.xdmf_path());
  EXPECT_TRUE(xml_balanced(x)) << x;
  EXPECT_EQ(count(x, "<Time "), 1);
  EXPECT_NE(x.find("<Time Value=\"2.5\"/>"), std::string::npos);
  EXPECT_EQ(x.find("displacement"), std::string::npos);
  PetscInt bs = 0;
  EXPECT_EQ(load_vec(dir_ / "bare_000003.h5", "geometry", &bs), s.points);
}

TEST_F(OutputFiles, XdmfSeriesErrors) {
  write_raw(dir_ / "plain", "x");
  mlshell::XdmfSeries blocked(dir_ / "plain" / "sub", "s");
  const std::string msg = output_error_of([&] { blocked.add_frame(0, 0.0, strip(0.0)); });
  EXPECT_NE(msg.find((dir_ / "plain" / "sub").string()), std::string::npos) << msg;

  mlshell::XdmfSeries series(dir_, "s");
  auto bad = strip(0.0);
  bad.displacement.pop_back();
  EXPECT_THROW(series.add_frame(0, 0.0, bad), std::invalid_argument);
  EXPECT_THROW(series.add_frame(0, 0.0, mlshell::SurfaceSample{}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(series.xdmf_path()));
  EXPECT_TRUE(temporaries_under(dir_).empty());
}

// --- CSV --------------------------------------------------------------------------------------

TEST_F(OutputFiles, CsvQuotingAndRows) {
  const fs::path p = dir_ / "tables" / "history.csv";
  mlshell::CsvTable t(p, {"step", "energy, total", "note"});
  EXPECT_EQ(read_text(p), "step,\"energy, total\",note\n");
  t.append({0LL, 0.1, std::string("plain")});
  t.append({1LL, -2.0, std::string("say \"hi\", then\nleave")});
  t.append({std::numeric_limits<long long>::max(), 1e300, std::string("")});
  EXPECT_EQ(read_text(p),
            "step,\"energy, total\",note\n"
            "0,0.1,plain\n"
            "1,-2,\"say \"\"hi\"\", then\nleave\"\n"
            "9223372036854775807,1e+300,\n");
  EXPECT_THROW(t.append({1LL, 2.0}), std::invalid_argument);
  EXPECT_THROW(t.append({1LL, 2.0, std::string("a"), std::string("b")}), std::invalid_argument);
  EXPECT_EQ(count(read_text(p), "\n"), 5);  // unchanged by the rejected rows
  EXPECT_TRUE(temporaries_under(dir_).empty());
}

// --- JSON -------------------------------------------------------------------------------------

TEST_F(OutputFiles, JsonEscapingAndScalars) {
  using mlshell::Json;
  EXPECT_EQ(Json("a\"b\\c\n\t\x01\x1f/é").dump(0), "\"a\\\"b\\\\c\\n\\t\\u0001\\u001f/é\"");
  EXPECT_EQ(Json(std::numeric_limits<double>::quiet_NaN()).dump(0), "null");
  EXPECT_EQ(Json(-std::numeric_limits<double>::infinity()).dump(0), "null");
  EXPECT_EQ(Json(0.1).dump(0), "0.1");
  EXPECT_EQ(Json(2.0).dump(0), "2.0");
  EXPECT_EQ(Json(1e300).dump(0), "1e+300");
  EXPECT_EQ(Json(0.1 + 0.2).dump(0), "0.30000000000000004");  // shortest, still exact
  EXPECT_EQ(Json(std::numeric_limits<long long>::min()).dump(0), "-9223372036854775808");
  EXPECT_EQ(Json(42).dump(0), "42");
  EXPECT_EQ(Json(true).dump(0), "true");
  EXPECT_EQ(Json().dump(0), "null");
  EXPECT_THROW(Json(1).set("k", 2), std::logic_error);
  EXPECT_THROW(Json().set("k", 2), std::logic_error);
}

TEST_F(OutputFiles, JsonNestingOrderAndReplacement) {
  using mlshell::Json;
  Json inner = Json::Object{};
  inner.set("ok", true);
  Json doc = Json::Object{{"name", "run"}};
  doc.set("steps", 3)
      .set("residuals", Json::array({1.0, 0.5, std::nan("")}))
      .set("empty", Json::Array{})
      .set("inner", inner)
      .set("name", "renamed");  // replaced in place, order kept
  inner.set("ok", false);       // copies do not alias
  EXPECT_EQ(doc.dump(0),
            "{\"name\":\"renamed\",\"steps\":3,\"residuals\":[1.0,0.5,null],\"empty\":[],"
            "\"inner\":{\"ok\":true}}");
  EXPECT_EQ(doc.dump(),
            "{\n"
            "  \"name\": \"renamed\",\n"
            "  \"steps\": 3,\n"
            "  \"residuals\": [\n"
            "    1.0,\n"
            "    0.5,\n"
            "    null\n"
            "  ],\n"
            "  \"empty\": [],\n"
            "  \"inner\": {\n"
            "    \"ok\": true\n"
            "  }\n"
            "}\n");
  EXPECT_EQ(Json(Json::Object{}).dump(), "{}\n");
}

// --- checkpoints ------------------------------------------------------------------------------

mlshell::Checkpoint sample_checkpoint() {
  mlshell::Checkpoint c;
  c.step = 1234;
  c.time = 0.1 + 0.2;
  c.scene_fingerprint = 0xfedcba9876543210ull;
  c.displacement = {1.0 / 3, -0.0, std::numeric_limits<double>::denorm_min(), 1e308, -7.5, 0.0};
  c.velocity = {std::numeric_limits<double>::quiet_NaN(), 2.0, -1e-300, 3.0, 4.0, 5.0};
  return c;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

TEST_F(OutputFiles, CheckpointRoundTripIsBitExact) {
  const fs::path p = dir_ / "ckpt" / "state.bin";
  const auto c = sample_checkpoint();
  mlshell::write_checkpoint(p, c);
  EXPECT_EQ(fs::file_size(p), 40u + 16u * 6u + 8u);  // header, two arrays, checksum
  EXPECT_EQ(read_text(p).substr(0, 8), "MLSHCKPT");
  const auto r = mlshell::read_checkpoint(p);
  EXPECT_EQ(r.step, c.step);
  EXPECT_EQ(std::memcmp(&r.time, &c.time, sizeof(double)), 0);
  EXPECT_EQ(r.scene_fingerprint, c.scene_fingerprint);
  EXPECT_TRUE(same_bits(r.displacement, c.displacement));
  EXPECT_TRUE(same_bits(r.velocity, c.velocity));

  mlshell::Checkpoint empty;
  empty.step = -1;
  mlshell::write_checkpoint(p, empty);
  const auto e = mlshell::read_checkpoint(p);
  EXPECT_EQ(e.step, -1);
  EXPECT_TRUE(e.displacement.empty());
  EXPECT_TRUE(temporaries_under(dir_).empty());

  auto mismatched = sample_checkpoint();
  mismatched.velocity.pop_back();
  EXPECT_THROW(mlshell::write_checkpoint(p, mismatched), std::invalid_argument);
}

TEST_F(OutputFiles, CheckpointRejectsDamagedAndForeignFiles) {
  const fs::path good = dir_ / "good.bin";
  mlshell::write_checkpoint(good, sample_checkpoint());
  const std::string bytes = read_text(good);

  // Each case: file content, and a word the message must contain besides the path.
  struct Case {
    const char* name;
    std::string content;
    const char* expect;
  };
  std::string flipped = bytes;
  flipped[60] ^= 0x01;  // inside the displacement array
  std::string version = bytes;
  version[8] = 2;
  std::string huge_n = bytes;
  for (int i = 32; i < 40; ++i) huge_n[i] = '\xff';
  std::string longer = bytes + "x";
  const std::vector<Case> cases = {
      {"truncated_body.bin", bytes.substr(0, bytes.size() - 1), "truncated"},
      {"truncated_header.bin", bytes.substr(0, 20), "truncated"},
      {"tiny.bin", bytes.substr(0, 3), "magic"},
      {"empty.bin", "", "magic"},
      {"corrupt.bin", flipped, "checksum"},
      {"version.bin", version, "version"},
      {"huge_n.bin", huge_n, "truncated"},
      {"trailing.bin", longer, "size"},
      {"foreign.bin", "solver: newton\nsteps: 10\n" + std::string(200, ' '), "magic"},
  };
  for (const auto& c : cases) {
    const fs::path p = dir_ / c.name;
    write_raw(p, c.content);
    const std::string msg = output_error_of([&] { mlshell::read_checkpoint(p); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << c.name << ": " << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.name << ": " << msg;
  }
  const fs::path missing = dir_ / "missing.bin";
  const std::string msg = output_error_of([&] { mlshell::read_checkpoint(missing); });
  EXPECT_NE(msg.find(missing.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
  EXPECT_NO_THROW(mlshell::read_checkpoint(good));
}

}  // namespace
