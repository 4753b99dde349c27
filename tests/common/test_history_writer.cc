// HistoryWriter: shapes, values and attributes read back with the HDF5 C API; rows on disk
// after flush() while the writer is still open; errors name the file and the dataset.
#include "common/history_writer.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
using ddafem::HistoryChannel;
using ddafem::HistoryWriter;
namespace fs = std::filesystem;

/// A fresh path in the temporary directory, unique per test and process.
fs::path temporary_file(const std::string& suffix)
{
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path path = fs::temp_directory_path() / ("ddafem_" + std::string(info->name()) + "_" +
                                                     std::to_string(::getpid()) + suffix);
  fs::remove(path);
  return path;
}

/// A read-only HDF5 file handle closed on scope exit.
class ReadOnlyFile
{
public:
  explicit ReadOnlyFile(const fs::path& path)
      : id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT))
  {
  }
  ~ReadOnlyFile()
  {
    if (id >= 0)
      H5Fclose(id);
  }
  ReadOnlyFile(const ReadOnlyFile&) = delete;
  ReadOnlyFile& operator=(const ReadOnlyFile&) = delete;
  hid_t id;
};

/// Shape of a dataset (empty if it cannot be opened).
std::vector<hsize_t> dataset_shape(hid_t file, const std::string& path)
{
  std::vector<hsize_t> dims;
  const hid_t dataset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (dataset < 0)
    return dims;
  const hid_t space = H5Dget_space(dataset);
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank > 0)
  {
    dims.resize(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  }
  H5Sclose(space);
  H5Dclose(dataset);
  return dims;
}

/// All values of a dataset of doubles, row-major.
std::vector<double> read_dataset(hid_t file, const std::string& path)
{
  const hid_t dataset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(dataset, 0) << path;
  if (dataset < 0)
    return {};
  const hid_t space = H5Dget_space(dataset);
  std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  if (!values.empty())
  {
    EXPECT_GE(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  }
  H5Sclose(space);
  H5Dclose(dataset);
  return values;
}

/// A fixed-length string attribute of the object at `object_path`.
std::string read_string_attribute(hid_t file, const std::string& object_path,
                                  const std::string& name)
{
  const hid_t attribute =
      H5Aopen_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(attribute, 0) << object_path << " @" << name;
  if (attribute < 0)
    return {};
  const hid_t type = H5Aget_type(attribute);
  EXPECT_EQ(H5Tget_class(type), H5T_STRING);
  EXPECT_EQ(H5Tis_variable_str(type), 0);
  std::string value(H5Tget_size(type), '\0');
  EXPECT_GE(H5Aread(attribute, type, value.data()), 0);
  H5Tclose(type);
  H5Aclose(attribute);
  value.resize(value.find('\0') == std::string::npos ? value.size() : value.find('\0'));
  return value;
}

std::vector<HistoryChannel> monitor_and_energy_channels()
{
  return {{"monitors/M1/stress", 3, "Pa", "(sxx, syy, sxy), tension positive"},
          {"monitors/M1/displacement", 2, "m", "(ux, uy) of the monitor point"},
          {"/energy/kinetic", 1, "J", "kinetic energy of the blocks"}};
}

/// The row appended at index i: time and the 6 values of monitor_and_energy_channels().
double time_of_row(std::size_t i)
{
  return 1.0e-5 * static_cast<double>(i);
}
std::vector<double> values_of_row(std::size_t i)
{
  const double x = static_cast<double>(i);
  return {1.0e6 * x, -2.0e6 * x, 0.5 + x, 1.0e-3 * x, -1.0e-3 * x, 0.25 * x * x};
}

TEST(HistoryWriter, WritesShapesValuesAndAttributes)
{
  const fs::path path = temporary_file(".h5");
  const std::size_t n_rows = 1000;
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels(), 64);
    writer.set_attribute("scene", "two blocks");
    writer.set_attribute("version", "0.0.0");
    writer.set_attribute("version", "0.1.0"); // replaces the previous value
    for (std::size_t i = 0; i < n_rows; ++i)
      writer.append(time_of_row(i), values_of_row(i));
    EXPECT_EQ(writer.n_rows(), n_rows);
  } // 1000 = 15 * 64 + 40: the last 40 rows are written by the destructor

  ReadOnlyFile file(path);
  ASSERT_GE(file.id, 0);
  EXPECT_EQ(dataset_shape(file.id, "/time"), std::vector<hsize_t>({n_rows}));
  EXPECT_EQ(dataset_shape(file.id, "/monitors/M1/stress"), std::vector<hsize_t>({n_rows, 3}));
  EXPECT_EQ(dataset_shape(file.id, "/monitors/M1/displacement"), std::vector<hsize_t>({n_rows, 2}));
  EXPECT_EQ(dataset_shape(file.id, "/energy/kinetic"), std::vector<hsize_t>({n_rows}));

  const auto time = read_dataset(file.id, "/time");
  const auto stress = read_dataset(file.id, "/monitors/M1/stress");
  const auto displacement = read_dataset(file.id, "/monitors/M1/displacement");
  const auto kinetic = read_dataset(file.id, "/energy/kinetic");
  ASSERT_EQ(time.size(), n_rows);
  ASSERT_EQ(stress.size(), 3 * n_rows);
  ASSERT_EQ(displacement.size(), 2 * n_rows);
  ASSERT_EQ(kinetic.size(), n_rows);
  for (std::size_t i = 0; i < n_rows; ++i)
  {
    const auto v = values_of_row(i);
    ASSERT_EQ(time[i], time_of_row(i)) << "row " << i;
    ASSERT_EQ(stress[3 * i + 0], v[0]) << "row " << i;
    ASSERT_EQ(stress[3 * i + 1], v[1]) << "row " << i;
    ASSERT_EQ(stress[3 * i + 2], v[2]) << "row " << i;
    ASSERT_EQ(displacement[2 * i + 0], v[3]) << "row " << i;
    ASSERT_EQ(displacement[2 * i + 1], v[4]) << "row " << i;
    ASSERT_EQ(kinetic[i], v[5]) << "row " << i;
  }

  EXPECT_EQ(read_string_attribute(file.id, "/time", "unit"), "s");
  EXPECT_EQ(read_string_attribute(file.id, "/monitors/M1/stress", "unit"), "Pa");
  EXPECT_EQ(read_string_attribute(file.id, "/monitors/M1/stress", "description"),
            "(sxx, syy, sxy), tension positive");
  EXPECT_EQ(read_string_attribute(file.id, "/monitors/M1/displacement", "unit"), "m");
  EXPECT_EQ(read_string_attribute(file.id, "/energy/kinetic", "unit"), "J");
  EXPECT_EQ(read_string_attribute(file.id, "/", "scene"), "two blocks");
  EXPECT_EQ(read_string_attribute(file.id, "/", "version"), "0.1.0");
  fs::remove(path);
}

TEST(HistoryWriter, RowsAreOnDiskAfterFlushWhileTheWriterIsOpen)
{
  const fs::path path = temporary_file(".h5");
  const fs::path copy = temporary_file("_copy.h5");
  HistoryWriter writer(path.string(), monitor_and_energy_channels(), 64);
  for (std::size_t i = 0; i < 100; ++i)
    writer.append(time_of_row(i), values_of_row(i));
  writer.flush();

  // The bytes on disk form a complete file: copy them (as a crash would leave them) and read.
  fs::copy_file(path, copy);
  {
    ReadOnlyFile file(copy);
    ASSERT_GE(file.id, 0);
    EXPECT_EQ(dataset_shape(file.id, "/monitors/M1/stress"), std::vector<hsize_t>({100, 3}));
    const auto kinetic = read_dataset(file.id, "/energy/kinetic");
    ASSERT_EQ(kinetic.size(), 100u);
    EXPECT_EQ(kinetic[99], values_of_row(99)[5]);
  }
  // A second, read-only handle on the open file in this process also sees the rows.
  {
    ReadOnlyFile file(path);
    ASSERT_GE(file.id, 0);
    EXPECT_EQ(dataset_shape(file.id, "/time"), std::vector<hsize_t>({100}));
    EXPECT_EQ(read_dataset(file.id, "/time").back(), time_of_row(99));
  }

  // Appending continues after flush().
  for (std::size_t i = 100; i < 130; ++i)
    writer.append(time_of_row(i), values_of_row(i));
  writer.flush();
  {
    ReadOnlyFile file(path);
    ASSERT_GE(file.id, 0);
    const auto displacement = read_dataset(file.id, "/monitors/M1/displacement");
    ASSERT_EQ(displacement.size(), 2u * 130u);
    EXPECT_EQ(displacement[2 * 129 + 1], values_of_row(129)[4]);
  }
  fs::remove(copy);
  fs::remove(path);
}

// A run stopped by an error (its disk may be full) does not flush again while it unwinds: the
// bytes on disk are the last flush's file, which HDF5 opens, with every dataset at its rows.
TEST(HistoryWriter, AnErrorUnwindingLeavesTheLastFlush)
{
  const fs::path path = temporary_file(".h5");
  const fs::path copy = temporary_file("_copy.h5");
  try
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels(), 16);
    for (std::size_t i = 0; i < 40; ++i)
      writer.append(time_of_row(i), values_of_row(i));
    writer.flush();
    for (std::size_t i = 40; i < 100; ++i) // written in blocks of 16, never flushed
      writer.append(time_of_row(i), values_of_row(i));
    throw std::runtime_error("the run fails");
  }
  catch (const std::runtime_error&)
  {
  }
  fs::copy_file(path, copy); // what a reader finds on disk
  ReadOnlyFile file(copy);
  ASSERT_GE(file.id, 0);
  const auto time = read_dataset(file.id, "/time");
  ASSERT_GE(time.size(), 40u);
  EXPECT_EQ(dataset_shape(file.id, "/monitors/M1/stress"), std::vector<hsize_t>({time.size(), 3}));
  const auto kinetic = read_dataset(file.id, "/energy/kinetic");
  ASSERT_EQ(kinetic.size(), time.size());
  EXPECT_EQ(kinetic[39], values_of_row(39)[5]);
  EXPECT_EQ(time[39], time_of_row(39));
  fs::remove(copy);
  fs::remove(path);
}

// A resumed run reopens the file, cuts it back to the checkpoint's rows and appends after them:
// the file ends as if the run had never stopped.
TEST(HistoryWriter, ReopenCutsBackToTheCheckpointsRowsAndGoesOn)
{
  const fs::path path = temporary_file(".h5");
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels(), 16);
    writer.set_attribute("scene", "two blocks");
    for (std::size_t i = 0; i < 70; ++i) // the checkpoint counted 50; 20 more were flushed
      writer.append(time_of_row(i), values_of_row(i));
  }
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels(), HistoryWriter::Reopen{50},
                         16);
    EXPECT_EQ(writer.n_rows(), 50u);
    for (std::size_t i = 50; i < 120; ++i)
      writer.append(time_of_row(i), values_of_row(i));
  }
  ReadOnlyFile file(path);
  ASSERT_GE(file.id, 0);
  const auto time = read_dataset(file.id, "/time");
  ASSERT_EQ(time.size(), 120u);
  EXPECT_EQ(dataset_shape(file.id, "/monitors/M1/stress"), std::vector<hsize_t>({120, 3}));
  const auto stress = read_dataset(file.id, "/monitors/M1/stress");
  const auto kinetic = read_dataset(file.id, "/energy/kinetic");
  for (std::size_t i = 0; i < 120; ++i)
  {
    EXPECT_EQ(time[i], time_of_row(i));
    EXPECT_EQ(stress[3 * i + 1], values_of_row(i)[1]);
    EXPECT_EQ(kinetic[i], values_of_row(i)[5]);
  }
  EXPECT_EQ(read_string_attribute(file.id, "/", "scene"), "two blocks");
  fs::remove(path);
}

TEST(HistoryWriter, ReopenRefusesAFileShorterThanTheCheckpoint)
{
  const fs::path path = temporary_file(".h5");
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels(), 16);
    for (std::size_t i = 0; i < 10; ++i)
      writer.append(time_of_row(i), values_of_row(i));
  }
  try
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels(), HistoryWriter::Reopen{50});
    FAIL() << "a file of 10 rows reopened at 50";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("10 rows, the checkpoint needs 50"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  fs::remove(path);
}

TEST(HistoryWriter, EmptyRunLeavesEmptyDatasets)
{
  const fs::path path = temporary_file(".h5");
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels());
    EXPECT_EQ(writer.n_rows(), 0u);
  }
  ReadOnlyFile file(path);
  ASSERT_GE(file.id, 0);
  EXPECT_EQ(dataset_shape(file.id, "/time"), std::vector<hsize_t>({0}));
  EXPECT_EQ(dataset_shape(file.id, "/monitors/M1/stress"), std::vector<hsize_t>({0, 3}));
  fs::remove(path);
}

TEST(HistoryWriter, ErrorsNameTheFileAndTheDataset)
{
  // The file cannot be created.
  const std::string missing_dir = (temporary_file("_missing") / "histories.h5").string();
  try
  {
    HistoryWriter writer(missing_dir, monitor_and_energy_channels());
    FAIL() << "expected std::runtime_error";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE(std::string(error.what()).find(missing_dir), std::string::npos) << error.what();
  }

  // The same dataset twice.
  const fs::path path = temporary_file(".h5");
  auto channels = monitor_and_energy_channels();
  channels.push_back({"monitors/M1/stress", 3, "Pa", "again"});
  try
  {
    HistoryWriter writer(path.string(), channels);
    FAIL() << "expected std::runtime_error";
  }
  catch (const std::runtime_error& error)
  {
    const std::string message = error.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("monitors/M1/stress"), std::string::npos) << message;
  }

  // Misuse.
  EXPECT_THROW(HistoryWriter(path.string(), {{"energy/kinetic", 0, "J", ""}}),
               std::invalid_argument);
  EXPECT_THROW(HistoryWriter(path.string(), monitor_and_energy_channels(), 0),
               std::invalid_argument);
  {
    HistoryWriter writer(path.string(), monitor_and_energy_channels());
    EXPECT_THROW(writer.append(0.0, {1.0, 2.0}), std::invalid_argument);
    EXPECT_EQ(writer.n_rows(), 0u);
  }
  fs::remove(path);
}

} // namespace
