// VtuSeriesWriter: two snapshots of a triangle and a concave L-shaped hexagon, read back with a
// minimal parser (sizes, cell types, offsets, connectivity, values) and the PVD collection.
#include "dda/vtu_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
using ddafem::dda::BlockSnapshot;
using ddafem::dda::Point;
using ddafem::dda::Vector2;
using ddafem::dda::Voigt;
using ddafem::dda::VtuSeriesWriter;
namespace fs = std::filesystem;

/// A fresh, not yet existing path in the temporary directory, unique per test and process.
fs::path temporary_path(const std::string& suffix)
{
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path path = fs::temp_directory_path() / ("ddafem_" + std::string(info->name()) + "_" +
                                                     std::to_string(::getpid()) + suffix);
  fs::remove_all(path);
  return path;
}

std::string read_text(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Value of the first attribute `name="..."` in `text` (empty if absent).
std::string attribute(const std::string& text, const std::string& name)
{
  std::smatch match;
  if (std::regex_search(text, match, std::regex("\\b" + name + "=\"([^\"]*)\"")))
    return match[1];
  return {};
}

/// The first opening tag of element `element`.
std::string opening_tag(const std::string& text, const std::string& element)
{
  std::smatch match;
  if (std::regex_search(text, match, std::regex("<" + element + "\\b[^>]*>")))
    return match[0];
  return {};
}

/// The opening tag of the DataArray called `name`.
std::string data_array_tag(const std::string& text, const std::string& name)
{
  std::smatch match;
  if (std::regex_search(text, match, std::regex("<DataArray[^>]*Name=\"" + name + "\"[^>]*>")))
    return match[0];
  return {};
}

/// The numbers between `<DataArray ... Name="NAME" ...>` (or, for an empty name, the first
/// DataArray after <Points>) and `</DataArray>`.
std::vector<double> data_array(const std::string& text, const std::string& name)
{
  std::size_t start = std::string::npos;
  if (name.empty())
    start = text.find("<DataArray", text.find("<Points>"));
  else
    start = text.find(data_array_tag(text, name));
  EXPECT_NE(start, std::string::npos) << "no DataArray '" << name << "'";
  if (start == std::string::npos)
    return {};
  const std::size_t begin = text.find('>', start) + 1;
  const std::size_t end = text.find("</DataArray>", begin);
  std::istringstream in(text.substr(begin, end - begin));
  std::vector<double> values;
  std::string word;
  while (in >> word)
    values.push_back(std::stod(word));
  return values;
}

/// A triangle (block 0) and an L-shaped hexagon, concave at (3, 1) (block 1), moved by
/// `shift` [m].
std::vector<BlockSnapshot> two_blocks(double shift)
{
  BlockSnapshot triangle;
  triangle.id = 0;
  triangle.material = 0;
  triangle.vertices = {Point(0.0, 0.0), Point(1.0, 0.0), Point(0.1 + 0.2, 1.0)};
  triangle.stress = Voigt(1.0e6, -2.0e6, 5.0e5);

  BlockSnapshot hexagon;
  hexagon.id = 7;
  hexagon.material = 2;
  hexagon.vertices = {Point(2.0, 0.0), Point(4.0, 0.0), Point(4.0, 1.0),
                      Point(3.0, 1.0), Point(3.0, 2.0), Point(2.0, 2.0)};
  hexagon.velocity = Vector2(-0.25, 1.0 / 3.0);
  hexagon.stress = Voigt(-3.0e6, 0.0, 0.0);

  for (BlockSnapshot* block : {&triangle, &hexagon})
  {
    for (auto& vertex : block->vertices)
      vertex.x() += shift;
    block->displacement = Vector2(shift, 0.0);
  }
  return {triangle, hexagon};
}

TEST(VtuSeriesWriter, WritesPolygonsCellDataAndCollection)
{
  const fs::path dir = temporary_path("_dir") / "nested";
  VtuSeriesWriter writer(dir.string(), "blocks");
  const std::string first = writer.write(0.0, two_blocks(0.0));
  const std::string second = writer.write(1.0e-3, two_blocks(0.5));
  EXPECT_EQ(writer.n_written(), 2u);
  EXPECT_EQ(fs::path(first), dir / "blocks_00000.vtu");
  EXPECT_EQ(fs::path(second), dir / "blocks_00001.vtu");
  EXPECT_FALSE(fs::exists(dir / "blocks.pvd.tmp"));

  const std::string text = read_text(second);
  const std::string root = opening_tag(text, "VTKFile");
  EXPECT_EQ(attribute(root, "type"), "UnstructuredGrid");
  EXPECT_EQ(attribute(root, "version"), "0.1");
  EXPECT_EQ(attribute(root, "byte_order"), "LittleEndian");
  EXPECT_EQ(attribute(text, "NumberOfPoints"), "9");
  EXPECT_EQ(attribute(text, "NumberOfCells"), "2");
  EXPECT_EQ(data_array(text, "TimeValue"), std::vector<double>({1.0e-3}));

  const auto points = data_array(text, "");
  ASSERT_EQ(points.size(), 27u);
  EXPECT_EQ(points[6], 0.1 + 0.2 + 0.5); // lossless: the exact double written
  EXPECT_EQ(points[7], 1.0);
  EXPECT_EQ(points[8], 0.0);
  EXPECT_EQ(points[6 * 3 + 0], 3.5); // point 6: the concave vertex (3, 1), shifted
  EXPECT_EQ(points[6 * 3 + 1], 1.0);

  EXPECT_EQ(data_array(text, "connectivity"), std::vector<double>({0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(data_array(text, "offsets"), std::vector<double>({3, 9}));
  EXPECT_EQ(data_array(text, "types"), std::vector<double>({7, 7}));
  EXPECT_EQ(attribute(data_array_tag(text, "types"), "type"), "UInt8");

  EXPECT_EQ(attribute(data_array_tag(text, "block_id"), "type"), "Int64");
  EXPECT_EQ(data_array(text, "block_id"), std::vector<double>({0, 7}));
  EXPECT_EQ(attribute(data_array_tag(text, "material"), "type"), "Int32");
  EXPECT_EQ(data_array(text, "material"), std::vector<double>({0, 2}));
  EXPECT_EQ(attribute(data_array_tag(text, "displacement"), "NumberOfComponents"), "3");
  EXPECT_EQ(data_array(text, "displacement"), std::vector<double>({0.5, 0, 0, 0.5, 0, 0}));
  EXPECT_EQ(data_array(text, "velocity"), std::vector<double>({0, 0, 0, -0.25, 1.0 / 3.0, 0}));

  const std::string stress_tag = data_array_tag(text, "stress");
  EXPECT_EQ(attribute(stress_tag, "type"), "Float64");
  EXPECT_EQ(attribute(stress_tag, "NumberOfComponents"), "3");
  EXPECT_EQ(attribute(stress_tag, "ComponentName0"), "sxx");
  EXPECT_EQ(attribute(stress_tag, "ComponentName1"), "syy");
  EXPECT_EQ(attribute(stress_tag, "ComponentName2"), "sxy");
  EXPECT_EQ(data_array(text, "stress"),
            std::vector<double>({1.0e6, -2.0e6, 5.0e5, -3.0e6, 0.0, 0.0}));

  // Plane stress von Mises: sqrt(1 + 2 + 4 + 0.75) MPa for the triangle; |sxx| for uniaxial.
  const auto von_mises = data_array(text, "von_mises");
  ASSERT_EQ(von_mises.size(), 2u);
  EXPECT_NEAR(von_mises[0], std::sqrt(7.75) * 1.0e6, 1.0e-6);
  EXPECT_NEAR(von_mises[1], 3.0e6, 1.0e-6);

  // The first file holds the unshifted snapshot.
  EXPECT_EQ(data_array(read_text(first), "")[6], 0.1 + 0.2);

  // The collection lists both files with their times.
  const std::string pvd = read_text(dir / "blocks.pvd");
  EXPECT_EQ(attribute(opening_tag(pvd, "VTKFile"), "type"), "Collection");
  const std::regex data_set("<DataSet timestep=\"([^\"]*)\"[^>]*file=\"([^\"]*)\"");
  std::vector<double> times;
  std::vector<std::string> files;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), data_set);
       it != std::sregex_iterator(); ++it)
  {
    times.push_back(std::stod((*it)[1]));
    files.push_back((*it)[2]);
  }
  EXPECT_EQ(times, std::vector<double>({0.0, 1.0e-3}));
  EXPECT_EQ(files, std::vector<std::string>({"blocks_00000.vtu", "blocks_00001.vtu"}));

  fs::remove_all(dir.parent_path());
}

TEST(VtuSeriesWriter, EmptySnapshotIsValid)
{
  const fs::path dir = temporary_path("_dir");
  VtuSeriesWriter writer(dir.string(), "empty");
  const std::string text = read_text(writer.write(0.0, std::vector<BlockSnapshot>{}));
  EXPECT_EQ(attribute(text, "NumberOfPoints"), "0");
  EXPECT_EQ(attribute(text, "NumberOfCells"), "0");
  EXPECT_TRUE(data_array(text, "offsets").empty());
  fs::remove_all(dir);
}

TEST(VtuSeriesWriter, FailureNamesThePath)
{
  // The output "directory" is an existing regular file.
  const fs::path file = temporary_path("_file");
  std::ofstream(file) << "not a directory\n";
  VtuSeriesWriter writer(file.string(), "blocks");
  try
  {
    writer.write(0.0, two_blocks(0.0));
    FAIL() << "expected std::runtime_error";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
  EXPECT_EQ(writer.n_written(), 0u);
  fs::remove(file);

  EXPECT_THROW(VtuSeriesWriter(".", ""), std::invalid_argument);
}

} // namespace
