// XDMF 3 time series backed by one HDF5 file per frame, written through PETSc's HDF5 viewer on
// the series' communicator: every rank writes its slice of each dataset (parallel HDF5), rank 0
// alone handles the file names (temporary, rename) and the XDMF text.
//
// The HDF5 viewer is created with the generic PetscViewerCreate/SetType/FileSetMode/
// FileSetName sequence, which is exactly what PetscViewerHDF5Open does, because including
// <petscviewerhdf5.h> needs HDF5's own headers on the include path and the build only gets
// PETSc's flags from pkg-config. VecView/ISView dispatch to the HDF5 writers by viewer type.
//
// Dataset layouts (checked with the HDF5 C API against this PETSc build): a sequential Vec of
// block size 3 becomes an N×3 H5T_IEEE_F64 dataset, an IS of block size 4 an M×4 dataset of the
// native PetscInt type. No timestep is ever set on the viewer, so no extra time dimension is
// added.
#include <petscis.h>
#include <petscvec.h>
#include <petscviewer.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <type_traits>

#include "io_util.hpp"

namespace mlshell {
namespace {

static_assert(std::is_same_v<PetscScalar, double>,
              "XDMF output assumes a real double-precision PETSc build");

using io_detail::check_petsc;

// Owns the PETSc objects a SurfaceSample is wrapped in, so they are released on every path.
struct SampleObjects {
  Vec geometry = nullptr, displacement = nullptr;
  std::vector<Vec> fields;
  IS topology = nullptr;
  ~SampleObjects() {
    for (Vec& v : fields) VecDestroy(&v);
    if (geometry) VecDestroy(&geometry);
    if (displacement) VecDestroy(&displacement);
    if (topology) ISDestroy(&topology);
  }
};

PetscInt to_petsc_size(std::size_t n, const std::filesystem::path& file) {
  if (n > static_cast<std::size_t>(std::numeric_limits<PetscInt>::max()))
    throw OutputError("cannot write '" + file.string() + "': " + std::to_string(n) +
                      " values exceed the PetscInt range of this PETSc build");
  return static_cast<PetscInt>(n);
}

/// A sequential Vec borrowing `data` (no copy); block size 3 makes the dataset N×3.
Vec borrow_vector(const std::vector<double>& data, const char* name,
                  const std::filesystem::path& file, PetscInt block = 3) {
  Vec v;
  check_petsc(VecCreateSeqWithArray(PETSC_COMM_SELF, block, to_petsc_size(data.size(), file),
                                    data.data(), &v),
              file, "VecCreateSeqWithArray");
  check_petsc(PetscObjectSetName(reinterpret_cast<PetscObject>(v), name), file,
              "PetscObjectSetName");
  return v;
}

void write_frame_h5(MPI_Comm comm, const std::filesystem::path& file, const FrameData& frame) {
  std::filesystem::path tmp;
  io_detail::on_rank_zero(comm, [&] {
    io_detail::create_parent_folder(file);
    tmp = io_detail::temporary_path_for(file);
  });
  // Every rank opens rank 0's temporary name.
  tmp = io_detail::broadcast(comm, tmp.string());
  PetscViewer viewer = nullptr;
  try {
    check_petsc(PetscViewerCreate(comm, &viewer), file, "PetscViewerCreate");
    check_petsc(PetscViewerSetType(viewer, PETSCVIEWERHDF5), file, "PetscViewerSetType");
    check_petsc(PetscViewerFileSetMode(viewer, FILE_MODE_WRITE), file, "PetscViewerFileSetMode");
    check_petsc(PetscViewerFileSetName(viewer, tmp.c_str()), file, "PetscViewerFileSetName");
    check_petsc(VecView(frame.geometry, viewer), file, "VecView (geometry)");
    // Indices are PetscInt in the file (an IS cannot hold anything else).
    check_petsc(ISView(frame.topology, viewer), file, "ISView (topology)");
    if (frame.displacement)
      check_petsc(VecView(frame.displacement, viewer), file, "VecView (displacement)");
    for (const auto& field : frame.cell_fields)
      check_petsc(VecView(field.second, viewer), file, "VecView (cell field)");
    // Destroying the viewer closes the file (collectively).
    check_petsc(PetscViewerDestroy(&viewer), file, "PetscViewerDestroy (closing the file)");
  } catch (...) {
    if (viewer) PetscViewerDestroy(&viewer);
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
  io_detail::on_rank_zero(comm, [&] { io_detail::commit_temporary(tmp, file); });
}

// Escapes the characters with a meaning in XML text and attribute values.
std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string data_item(std::int64_t rows, int cols, const char* number_type, std::size_t precision,
                      const std::string& h5, const std::string& dataset) {
  return "<DataItem Dimensions=\"" + std::to_string(rows) + " " + std::to_string(cols) +
         "\" NumberType=\"" + number_type + "\" Precision=\"" + std::to_string(precision) +
         "\" Format=\"HDF\">" + xml_escape(h5) + ":/" + dataset + "</DataItem>";
}

}  // namespace

XdmfSeries::XdmfSeries(std::filesystem::path dir, std::string stem, MPI_Comm comm)
    : comm_(comm), dir_(std::move(dir)), stem_(std::move(stem)) {
  if (stem_.empty() || stem_.find('/') != std::string::npos)
    throw std::invalid_argument("XdmfSeries: the stem must be a non-empty file name, got '" +
                                stem_ + "'");
  xdmf_ = dir_ / (stem_ + ".xdmf");
}

XdmfSeries::~XdmfSeries() = default;

void XdmfSeries::add_frame(int step, double time, const SurfaceSample& surface) {
  int size;
  MPI_Comm_size(comm_, &size);
  if (size != 1)
    throw std::logic_error("XdmfSeries::add_frame: a SurfaceSample is one process's data; a "
                           "series on several ranks takes a FrameData");
  io_detail::check_surface(surface, "XdmfSeries::add_frame");
  // HDF5 datasets of zero extent are not worth supporting: a frame without points is a bug.
  if (surface.points.empty() || surface.cells.empty())
    throw std::invalid_argument("XdmfSeries::add_frame: the surface has no points or no cells");
  const std::filesystem::path file = dir_ / h5_name(step);
  SampleObjects o;
  o.geometry = borrow_vector(surface.points, "geometry", file);
  // check_surface has bounded the indices by the point count, which to_petsc_size has bounded
  // by PetscInt's range.
  const std::vector<PetscInt> idx(surface.cells.begin(), surface.cells.end());
  check_petsc(ISCreateGeneral(PETSC_COMM_SELF, to_petsc_size(idx.size(), file), idx.data(),
                              PETSC_USE_POINTER, &o.topology),
              file, "ISCreateGeneral");
  check_petsc(ISSetBlockSize(o.topology, surface.cell_size), file, "ISSetBlockSize");
  check_petsc(PetscObjectSetName(reinterpret_cast<PetscObject>(o.topology), "topology"), file,
              "PetscObjectSetName");
  FrameData frame{o.geometry, nullptr, o.topology, surface.cell_size, {}};
  if (!surface.displacement.empty())
    frame.displacement = o.displacement = borrow_vector(surface.displacement, "displacement", file);
  for (const auto& [name, values] : surface.cell_data) {
    o.fields.push_back(borrow_vector(values, ("cell_" + name).c_str(), file, 1));
    frame.cell_fields.emplace_back(name, o.fields.back());
  }
  add_frame(step, time, frame);
}

std::string XdmfSeries::h5_name(int step) const {
  if (step < 0) throw std::invalid_argument("XdmfSeries::add_frame: negative step");
  char name[32];
  std::snprintf(name, sizeof name, "_%06d.h5", step);
  return stem_ + name;
}

void XdmfSeries::add_frame(int step, double time, const FrameData& frame) {
  const std::string h5 = h5_name(step);
  PetscInt npoints = 0, ncells = 0;
  if (!frame.geometry || !frame.topology ||
      VecGetSize(frame.geometry, &npoints) || ISGetSize(frame.topology, &ncells) || npoints == 0 ||
      ncells == 0)
    throw std::invalid_argument("XdmfSeries::add_frame: the frame has no points or no cells");
  // The HDF5 file is complete (renamed into place) before the XDMF that lists it is rewritten.
  write_frame_h5(comm_, dir_ / h5, frame);

  Frame f{step, time, h5, npoints / 3, ncells / frame.cell_size, frame.displacement != nullptr,
          frame.cell_size, {}};
  for (const auto& field : frame.cell_fields) f.cell_fields.push_back(field.first);
  // A restarted run may repeat a step: its new file replaced the old one, so replace the entry.
  auto same =
      std::find_if(frames_.begin(), frames_.end(), [&](const Frame& g) { return g.step == step; });
  if (same != frames_.end())
    *same = f;
  else
    frames_.push_back(f);
  io_detail::on_rank_zero(comm_, [&] { write_xdmf(); });
}

void XdmfSeries::write_xdmf() const {
  std::string x;
  x += "<?xml version=\"1.0\" ?>\n";
  x += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  x += "<Xdmf Version=\"3.0\">\n";
  x += "  <Domain>\n";
  x += "    <Grid Name=\"" + xml_escape(stem_) +
       "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const Frame& g : frames_) {
    char grid[32];
    std::snprintf(grid, sizeof grid, "step_%06d", g.step);
    x += "      <Grid Name=\"" + std::string(grid) + "\" GridType=\"Uniform\">\n";
    x += "        <Time Value=\"" + io_detail::format_double(g.time) + "\"/>\n";
    x += std::string("        <Topology TopologyType=\"") +
         (g.cell_size == 3 ? "Triangle" : "Quadrilateral") + "\" NumberOfElements=\"" +
         std::to_string(g.ncells) + "\">\n";
    x += "          " +
         data_item(g.ncells, g.cell_size, "Int", sizeof(PetscInt), g.h5, "topology") + "\n";
    x += "        </Topology>\n";
    x += "        <Geometry GeometryType=\"XYZ\">\n";
    x += "          " + data_item(g.npoints, 3, "Float", sizeof(double), g.h5, "geometry") + "\n";
    x += "        </Geometry>\n";
    if (g.displacement) {
      x += "        <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n";
      x += "          " + data_item(g.npoints, 3, "Float", sizeof(double), g.h5, "displacement") +
           "\n";
      x += "        </Attribute>\n";
    }
    for (const std::string& name : g.cell_fields) {
      x += "        <Attribute Name=\"" + xml_escape(name) +
           "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
      x += "          " + data_item(g.ncells, 1, "Float", sizeof(double), g.h5, "cell_" + name) +
           "\n";
      x += "        </Attribute>\n";
    }
    x += "      </Grid>\n";
  }
  x += "    </Grid>\n";
  x += "  </Domain>\n";
  x += "</Xdmf>\n";
  write_file_atomic(xdmf_, x);
}

}  // namespace mlshell
