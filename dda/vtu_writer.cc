#include "dda/vtu_writer.h"

#include "common/checkpoint_archive.h"
#include "common/vtk_collection.h"
#include "dda/vtu_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <type_traits>

namespace ddafem::dda
{
namespace
{
namespace fs = std::filesystem;
using namespace vtu;

/// Von Mises equivalent stress [Pa] of a plane stress state (sxx, syy, sxy) [Pa]:
/// sqrt(sxx^2 - sxx syy + syy^2 + 3 sxy^2).
double von_mises(const Voigt& stress)
{
  const double sxx = stress[0];
  const double syy = stress[1];
  const double sxy = stress[2];
  return std::sqrt(std::max(0.0, sxx * sxx - sxx * syy + syy * syy + 3.0 * sxy * sxy));
}

/// Points and cells of the blocks: their current vertices, block after block, z = 0 [m], and
/// one polygon per block over its own vertices.
void append_block_geometry(std::string& out, const std::vector<BlockSnapshot>& blocks)
{
  out += "      <Points>\n"
         "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& block : blocks)
    for (const auto& vertex : block.vertices)
      append_vector(out, vertex);
  out += close_array;
  out += "      </Points>\n";
  out += "      <Cells>\n";
  open_array(out, "Int64", "connectivity", 1);
  std::size_t point = 0;
  for (const auto& block : blocks)
  {
    out += "         ";
    for (std::size_t v = 0; v < block.vertices.size(); ++v, ++point)
    {
      out += ' ';
      append_integer(out, point);
    }
    out += '\n';
  }
  out += close_array;
  open_array(out, "Int64", "offsets", 1);
  std::size_t offset = 0;
  for (const auto& block : blocks)
  {
    offset += block.vertices.size();
    out += "          ";
    append_integer(out, offset);
    out += '\n';
  }
  out += close_array;
  append_column<int>(out, blocks, "UInt8", "types",
                     [](const BlockSnapshot&) { return vtk_polygon; });
  out += "      </Cells>\n";
}

/// Cell data of the blocks: one tuple per block.
void append_block_data(std::string& out, const std::vector<BlockSnapshot>& blocks)
{
  out += "      <CellData Scalars=\"von_mises\" Vectors=\"displacement\">\n";
  append_column<std::size_t>(out, blocks, "Int64", "block_id",
                             [](const BlockSnapshot& b) { return b.id; });
  append_column<std::size_t>(out, blocks, "Int32", "material",
                             [](const BlockSnapshot& b) { return b.material; });
  append_vector_column<BlockSnapshot>(out, blocks, "displacement", // [m]
                                      [](const BlockSnapshot& b) { return b.displacement; });
  append_vector_column<BlockSnapshot>(out, blocks, "velocity", // [m/s]
                                      [](const BlockSnapshot& b) { return b.velocity; });
  out += "        <DataArray type=\"Float64\" Name=\"stress\" NumberOfComponents=\"3\" "
         "ComponentName0=\"sxx\" ComponentName1=\"syy\" ComponentName2=\"sxy\" "
         "format=\"ascii\">\n"; // [Pa], tension positive
  for (const auto& block : blocks)
  {
    out += "          ";
    append_number(out, block.stress[0]);
    out += ' ';
    append_number(out, block.stress[1]);
    out += ' ';
    append_number(out, block.stress[2]);
    out += '\n';
  }
  out += close_array;
  append_column<double>(out, blocks, "Float64", "von_mises", // [Pa]
                        [](const BlockSnapshot& b) { return von_mises(b.stress); });
  out += "      </CellData>\n";
}

/// The complete text of one .vtu file.
std::string vtu_text(double time, const std::vector<BlockSnapshot>& blocks)
{
  std::size_t n_points = 0;
  for (const auto& block : blocks)
    n_points += block.vertices.size();
  std::string out;
  out.reserve(256 + 64 * n_points + 256 * blocks.size());
  open_piece(out, time, n_points, blocks.size());
  append_block_geometry(out, blocks);
  append_block_data(out, blocks);
  out += close_piece;
  return out;
}

std::string contact_vtu_text(double time, const std::vector<ContactSnapshot>& contacts)
{
  std::string out;
  out.reserve(512 + 256 * contacts.size());
  open_piece(out, time, contacts.size(), contacts.size());
  out += "      <Points>\n"
         "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const ContactSnapshot& c : contacts)
    append_vector(out, c.position);
  out += close_array;
  out += "      </Points>\n"
         "      <Cells>\n";
  // One vertex cell per point: connectivity k, offset k + 1.
  const auto append_cell_array = [&](const char* type, const char* name, auto value_of)
  {
    open_array(out, type, name, 1);
    for (std::size_t k = 0; k < contacts.size(); ++k)
    {
      out += "          ";
      append_integer(out, value_of(k));
      out += '\n';
    }
    out += close_array;
  };
  append_cell_array("Int64", "connectivity", [](std::size_t k) { return k; });
  append_cell_array("Int64", "offsets", [](std::size_t k) { return k + 1; });
  append_cell_array("UInt8", "types", [](std::size_t) { return vtk_vertex; });
  out += "      </Cells>\n"
         "      <CellData Scalars=\"state\" Vectors=\"normal\">\n";
  append_column<std::size_t>(out, contacts, "Int64", "id",
                             [](const ContactSnapshot& c) { return c.id; });
  append_column<std::size_t>(out, contacts, "Int64", "block_a",
                             [](const ContactSnapshot& c) { return c.block_a; });
  append_column<std::size_t>(out, contacts, "Int64", "block_b",
                             [](const ContactSnapshot& c) { return c.block_b; });
  append_column<int>(out, contacts, "Int32", "state",
                     [](const ContactSnapshot& c) { return static_cast<int>(c.state); });
  append_vector_column<ContactSnapshot>(out, contacts, "normal",
                                        [](const ContactSnapshot& c) { return c.normal; });
  append_column<double>(out, contacts, "Float64", "normal_force",
                        [](const ContactSnapshot& c) { return c.normal_force; });
  append_column<double>(out, contacts, "Float64", "shear_force",
                        [](const ContactSnapshot& c) { return c.shear_force; });
  append_column<double>(out, contacts, "Float64", "gap",
                        [](const ContactSnapshot& c) { return c.gap; });
  append_column<double>(out, contacts, "Float64", "slip",
                        [](const ContactSnapshot& c) { return c.slip; });
  out += "      </CellData>\n";
  out += close_piece;
  return out;
}

/// Points, cells and point data of the bolts: one polyline per bolt through its points.
void append_bolt_geometry(std::string& out, const std::vector<BoltSnapshot>& bolts)
{
  out += "      <Points>\n"
         "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const BoltSnapshot& b : bolts)
    for (const Point& p : b.points)
      append_vector(out, p);
  out += close_array;
  out += "      </Points>\n"
         "      <Cells>\n";
  open_array(out, "Int64", "connectivity", 1);
  std::size_t point = 0;
  for (const BoltSnapshot& b : bolts)
    for (std::size_t k = 0; k < b.points.size(); ++k, ++point)
    {
      out += "          ";
      append_integer(out, point);
      out += '\n';
    }
  out += close_array;
  open_array(out, "Int64", "offsets", 1);
  std::size_t offset = 0;
  for (const BoltSnapshot& b : bolts)
  {
    offset += b.points.size();
    out += "          ";
    append_integer(out, offset);
    out += '\n';
  }
  out += close_array;
  append_column<int>(out, bolts, "UInt8", "types",
                     [](const BoltSnapshot&) { return vtk_poly_line; });
  out += "      </Cells>\n"
         "      <PointData Scalars=\"point_axial_force\">\n";
  for (const auto& [name, values] : {std::pair{"point_axial_force", &BoltSnapshot::point_axial},
                                     std::pair{"point_shear_force", &BoltSnapshot::point_shear}})
  {
    open_array(out, "Float64", name, 1);
    for (const BoltSnapshot& b : bolts)
      for (const double v : b.*values)
      {
        out += "          ";
        append_number(out, v);
        out += '\n';
      }
    out += close_array;
  }
  out += "      </PointData>\n";
}

std::string bolt_vtu_text(double time, const std::vector<BoltSnapshot>& bolts)
{
  std::size_t n_points = 0;
  for (const BoltSnapshot& b : bolts)
    n_points += b.points.size();
  std::string out;
  out.reserve(512 + 160 * n_points + 160 * bolts.size());
  open_piece(out, time, n_points, bolts.size());
  append_bolt_geometry(out, bolts);
  out += "      <CellData Scalars=\"axial_force\">\n";
  append_column<std::size_t>(out, bolts, "Int64", "bolt_id",
                             [](const BoltSnapshot& b) { return b.id; });
  append_column<int>(out, bolts, "Int32", "type",
                     [](const BoltSnapshot& b) { return static_cast<int>(b.type); });
  append_column<double>(out, bolts, "Float64", "axial_force",
                        [](const BoltSnapshot& b) { return b.axial_force; });
  append_column<double>(out, bolts, "Float64", "shear_force",
                        [](const BoltSnapshot& b) { return b.shear_force; });
  append_column<int>(out, bolts, "Int32", "state",
                     [](const BoltSnapshot& b) { return static_cast<int>(b.state); });
  out += "      </CellData>\n";
  out += close_piece;
  return out;
}

} // namespace

VtuSeriesWriter::VtuSeriesWriter(std::string directory_name, std::string file_basename)
    : directory(std::move(directory_name)), basename(std::move(file_basename))
{
  if (basename.empty() || basename.find('/') != std::string::npos)
    throw std::invalid_argument("VtuSeriesWriter: basename '" + basename +
                                "' must be a non-empty file name without '/'");
}

std::string VtuSeriesWriter::write(double time, const std::vector<BlockSnapshot>& blocks)
{
  return write_text(time, vtu_text(time, blocks));
}

std::string VtuSeriesWriter::write(double time, const std::vector<ContactSnapshot>& contacts)
{
  return write_text(time, contact_vtu_text(time, contacts));
}

std::string VtuSeriesWriter::write(double time, const std::vector<BoltSnapshot>& bolts)
{
  return write_text(time, bolt_vtu_text(time, bolts));
}

std::string VtuSeriesWriter::write_text(double time, const std::string& text)
{
  const fs::path dir = directory.empty() ? fs::path(".") : fs::path(directory);
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir))
    throw std::runtime_error("cannot create the output directory '" + dir.string() +
                             "': " + (error ? error.message() : "not a directory"));

  // BASENAME_00000.vtu: five digits, more once the series passes 99999 files.
  char index[24];
  std::snprintf(index, sizeof(index), "%05zu", entries.size());
  const std::string name = basename + "_" + index + ".vtu";
  const fs::path path = dir / name;
  write_file_atomically(path, text);

  entries.emplace_back(time, name);
  write_pvd();
  return path.string();
}

void VtuSeriesWriter::write_pvd() const
{
  std::vector<CollectionDataSet> data_sets;
  for (const auto& [time, name] : entries)
    data_sets.push_back({time, 0, name});
  const fs::path dir = directory.empty() ? fs::path(".") : fs::path(directory);
  write_collection(dir / (basename + ".pvd"), data_sets);
}

void VtuSeriesWriter::save(CheckpointOut& archive) const
{
  archive << entries;
}

void VtuSeriesWriter::load(CheckpointIn& archive)
{
  archive >> entries;
  write_pvd();
}

} // namespace ddafem::dda
