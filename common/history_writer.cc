#include "common/history_writer.h"

#include <hdf5.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <utility>

namespace ddafem
{
namespace
{
/// Owns one HDF5 identifier and closes it with the matching H5?close function.
class Handle
{
public:
  using Closer = herr_t (*)(hid_t);

  Handle() = default;
  Handle(hid_t new_id, Closer new_closer) : id(new_id), closer(new_closer) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id(other.id), closer(other.closer) { other.id = -1; }
  Handle& operator=(Handle&& other) noexcept
  {
    if (this != &other)
    {
      reset();
      id = other.id;
      closer = other.closer;
      other.id = -1;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const { return id; }
  bool valid() const { return id >= 0; }
  /// Forgets the identifier without closing it.
  void release() { id = -1; }

  /// Closes the identifier; returns false if HDF5 reported a failure.
  bool reset()
  {
    bool ok = true;
    if (id >= 0 && closer != nullptr)
      ok = closer(id) >= 0;
    id = -1;
    return ok;
  }

private:
  hid_t id = -1;
  Closer closer = nullptr;
};

/// Collects the description of the innermost error on HDF5's default error stack.
herr_t take_innermost_message(unsigned n, const H5E_error2_t* error, void* client_data)
{
  if (n == 0 && error != nullptr && error->desc != nullptr)
    *static_cast<std::string*>(client_data) = error->desc;
  return 0;
}

/// The innermost HDF5 error message (empty if none), then clears the error stack.
std::string hdf5_error_message()
{
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, take_innermost_message, &message);
  H5Eclear2(H5E_DEFAULT);
  return message;
}

[[noreturn]] void throw_hdf5_error(const std::string& filename, const std::string& object,
                                   const std::string& action)
{
  std::string message = "HDF5 history file '" + filename + "'";
  if (!object.empty())
    message += ", object '" + object + "'";
  message += ": cannot " + action;
  const std::string detail = hdf5_error_message();
  if (!detail.empty())
    message += " (" + detail + ")";
  throw std::runtime_error(message);
}

/// Dataset paths are relative to the root group; a leading '/' is accepted and removed.
std::string normalized_path(const std::string& path)
{
  std::size_t first = 0;
  while (first < path.size() && path[first] == '/')
    ++first;
  return path.substr(first);
}

} // namespace

struct HistoryWriter::Impl
{
  std::string filename;
  std::vector<HistoryChannel> channels;
  std::size_t flush_every = 1;
  std::size_t n_values_per_row = 0; ///< sum of the channels' n_components

  Handle file;
  Handle time_dataset;
  std::vector<Handle> channel_datasets; ///< same order as `channels`

  std::size_t n_rows_written = 0; ///< rows already in the file
  /// A write or flush failed (a full disk): nothing more is written, the file keeps what its
  /// last flush left.
  bool failed = false;
  std::vector<double> time_buffer;          ///< buffered times [s]
  std::vector<std::vector<double>> buffers; ///< per channel: buffered rows, row-major

  /// Stops before a write that might not fit: HDF5 goes on past a failed write and leaves a
  /// file it cannot open again, so the free space of the file's disk (statvfs) is checked first
  /// against what the next write can need at most: the buffered rows, a new chunk and a few
  /// kB of metadata per dataset. On too little, the file keeps its last flush.
  void require_space()
  {
    std::size_t needed = 8 * time_buffer.size() + chunk_bytes(1) + 4096;
    for (std::size_t c = 0; c < channels.size(); ++c)
      needed += 8 * buffers[c].size() + chunk_bytes(channels[c].n_components) + 4096;
    const std::filesystem::path parent =
        std::filesystem::absolute(std::filesystem::path(filename)).parent_path();
    struct statvfs disk;
    if (statvfs(parent.c_str(), &disk) != 0)
      return; // not known: go on
    const auto available = static_cast<std::size_t>(disk.f_bavail) * disk.f_frsize;
    if (available >= needed)
      return;
    failed = true;
    throw std::runtime_error("HDF5 history file '" + filename + "': its disk is full (" +
                             std::to_string(available / 1024) + " kB free, up to " +
                             std::to_string(needed / 1024 + 1) +
                             " kB needed for the next rows); the file keeps the rows up to its "
                             "last flush");
  }

  /// About flush_every rows per chunk, within [64, 8192] rows.
  std::size_t rows_per_chunk() const { return std::clamp<std::size_t>(flush_every, 64, 8192); }
  std::size_t chunk_bytes(std::size_t n_components) const
  {
    return 8 * n_components * rows_per_chunk();
  }

  void throw_if_failed() const
  {
    if (failed)
      throw std::runtime_error("HDF5 history file '" + filename +
                               "': an earlier write failed, no more rows are written");
  }

  void check(herr_t status, const std::string& object, const std::string& action) const
  {
    if (status < 0)
      throw_hdf5_error(filename, object, action);
  }

  /// Sets a fixed-length string attribute (UTF-8, null-terminated) on `object`, replacing an
  /// existing attribute of the same name.
  void write_string_attribute(hid_t object, const std::string& object_name, const std::string& name,
                              const std::string& value) const
  {
    const std::string what = "attribute '" + name + "'";
    const htri_t exists = H5Aexists(object, name.c_str());
    if (exists < 0)
      throw_hdf5_error(filename, object_name, "query " + what);
    if (exists > 0)
      check(H5Adelete(object, name.c_str()), object_name, "replace " + what);

    Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    if (!type.valid())
      throw_hdf5_error(filename, object_name, "create the string type of " + what);
    check(H5Tset_size(type.get(), value.size() + 1), object_name, "size " + what);
    check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), object_name, "pad " + what);
    check(H5Tset_cset(type.get(), H5T_CSET_UTF8), object_name, "set the encoding of " + what);

    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    if (!space.valid())
      throw_hdf5_error(filename, object_name, "create the dataspace of " + what);
    Handle attribute(
        H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    if (!attribute.valid())
      throw_hdf5_error(filename, object_name, "create " + what);
    check(H5Awrite(attribute.get(), type.get(), value.c_str()), object_name, "write " + what);
    if (!attribute.reset())
      throw_hdf5_error(filename, object_name, "close " + what);
  }

  /// Creates an extendible, chunked dataset of doubles: 1D if n_components == 1, otherwise
  /// (unlimited rows) x n_components. Intermediate groups are created as needed.
  Handle create_dataset(const std::string& path, std::size_t n_components, const std::string& unit,
                        const std::string& description) const
  {
    const int rank = n_components == 1 ? 1 : 2;
    const hsize_t chunk_rows = rows_per_chunk();
    const hsize_t initial_dims[2] = {0, n_components};
    const hsize_t max_dims[2] = {H5S_UNLIMITED, n_components};
    const hsize_t chunk_dims[2] = {chunk_rows, n_components};

    Handle space(H5Screate_simple(rank, initial_dims, max_dims), H5Sclose);
    if (!space.valid())
      throw_hdf5_error(filename, path, "create the dataspace");
    Handle link_plist(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
    if (!link_plist.valid())
      throw_hdf5_error(filename, path, "create the link creation property list");
    check(H5Pset_create_intermediate_group(link_plist.get(), 1), path,
          "enable creation of intermediate groups");
    Handle create_plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    if (!create_plist.valid())
      throw_hdf5_error(filename, path, "create the dataset creation property list");
    check(H5Pset_chunk(create_plist.get(), rank, chunk_dims), path, "set the chunk size");

    Handle dataset(H5Dcreate2(file.get(), path.c_str(), H5T_IEEE_F64LE, space.get(),
                              link_plist.get(), create_plist.get(), H5P_DEFAULT),
                   H5Dclose);
    if (!dataset.valid())
      throw_hdf5_error(filename, path,
                       "create the dataset (a path used twice, or a parent that is a dataset?)");
    write_string_attribute(dataset.get(), path, "unit", unit);
    write_string_attribute(dataset.get(), path, "description", description);
    return dataset;
  }

  /// The channels and buffers, and HDF5's error handling (both constructors).
  void set_channels(const std::string& name, std::vector<HistoryChannel> new_channels,
                    std::size_t rows_per_flush)
  {
    if (rows_per_flush == 0)
      throw std::invalid_argument("HistoryWriter '" + name + "': flush_every must be >= 1");
    filename = name;
    flush_every = rows_per_flush;
    channels = std::move(new_channels);
    for (auto& channel : channels)
    {
      channel.path = normalized_path(channel.path);
      if (channel.path.empty() || channel.n_components == 0)
        throw std::invalid_argument("HistoryWriter '" + filename + "': channel '" + channel.path +
                                    "' needs a non-empty path and n_components >= 1");
      n_values_per_row += channel.n_components;
    }
    // A file whose close failed (a full disk) stays open inside HDF5, and HDF5's clean-up at
    // exit would flush it again and crash (exit 139): the files are closed here, never at exit.
    // Only the first call in a process takes effect (before HDF5 initialises); later ones fail
    // harmlessly.
    H5dont_atexit();
    // Errors are reported through exceptions; HDF5's own printing to stderr would duplicate
    // them.
    if (H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) < 0)
      throw_hdf5_error(filename, "", "silence HDF5's error printing");
    time_buffer.reserve(flush_every);
    buffers.resize(channels.size());
    for (std::size_t c = 0; c < channels.size(); ++c)
      buffers[c].reserve(flush_every * channels[c].n_components);
  }

  /// Opens an existing dataset of a resumed file and cuts it back to `rows` rows.
  Handle cut_dataset(const std::string& path, std::size_t n_components, std::size_t rows) const
  {
    Handle dataset(H5Dopen2(file.get(), path.c_str(), H5P_DEFAULT), H5Dclose);
    if (!dataset.valid())
      throw_hdf5_error(filename, path, "open the dataset to resume it");
    Handle space(H5Dget_space(dataset.get()), H5Sclose);
    hsize_t dims[2] = {0, 0};
    if (!space.valid() || H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0)
      throw_hdf5_error(filename, path, "read the dataset's size");
    if (dims[0] < rows)
      throw std::runtime_error("HDF5 history file '" + filename + "', dataset '" + path +
                               "': " + std::to_string(dims[0]) + " rows, the checkpoint needs " +
                               std::to_string(rows));
    const hsize_t cut[2] = {rows, n_components};
    check(H5Dset_extent(dataset.get(), cut), path, "cut the dataset back to the checkpoint");
    return dataset;
  }

  /// Writes rows [n_rows_written, n_rows_written + n_new) of one dataset from `data`
  /// (row-major, n_new x n_components). Idempotent: a failed write can be retried.
  void write_rows(const Handle& dataset, const std::string& path, std::size_t n_components,
                  const std::vector<double>& data) const
  {
    const hsize_t n_new = data.size() / n_components;
    const int rank = n_components == 1 ? 1 : 2;
    const hsize_t new_dims[2] = {n_rows_written + n_new, n_components};
    const hsize_t offset[2] = {n_rows_written, 0};
    const hsize_t count[2] = {n_new, n_components};

    check(H5Dset_extent(dataset.get(), new_dims), path, "extend the dataset");
    Handle file_space(H5Dget_space(dataset.get()), H5Sclose);
    if (!file_space.valid())
      throw_hdf5_error(filename, path, "get the dataspace");
    check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, offset, nullptr, count, nullptr),
          path, "select the new rows");
    Handle memory_space(H5Screate_simple(rank, count, nullptr), H5Sclose);
    if (!memory_space.valid())
      throw_hdf5_error(filename, path, "create the memory dataspace");
    check(H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(),
                   H5P_DEFAULT, data.data()),
          path, "write rows");
  }

  /// Writes the buffered rows of /time and of every channel, then empties the buffers.
  void write_buffered_rows()
  {
    if (time_buffer.empty())
      return;
    throw_if_failed();
    require_space();
    failed = true; // until every dataset has its rows
    write_rows(time_dataset, "time", 1, time_buffer);
    for (std::size_t c = 0; c < channels.size(); ++c)
      write_rows(channel_datasets[c], channels[c].path, channels[c].n_components, buffers[c]);
    failed = false;
    n_rows_written += time_buffer.size();
    time_buffer.clear();
    for (auto& buffer : buffers)
      buffer.clear();
  }
};

HistoryWriter::HistoryWriter(const std::string& filename, std::vector<HistoryChannel> channels,
                             std::size_t flush_every)
    : impl(std::make_unique<Impl>())
{
  impl->set_channels(filename, std::move(channels), flush_every);
  impl->file =
      Handle(H5Fcreate(filename.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!impl->file.valid())
    throw_hdf5_error(filename, "", "create the file");

  impl->time_dataset = impl->create_dataset("time", 1, "s", "simulated time");
  for (const HistoryChannel& channel : impl->channels)
    impl->channel_datasets.push_back(impl->create_dataset(channel.path, channel.n_components,
                                                          channel.unit, channel.description));
}

HistoryWriter::HistoryWriter(const std::string& filename, std::vector<HistoryChannel> channels,
                             Reopen reopen, std::size_t flush_every)
    : impl(std::make_unique<Impl>())
{
  impl->set_channels(filename, std::move(channels), flush_every);
  impl->file = Handle(H5Fopen(filename.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
  if (!impl->file.valid())
    throw_hdf5_error(filename, "", "open the file to resume it");
  impl->time_dataset = impl->cut_dataset("time", 1, reopen.rows);
  for (const HistoryChannel& channel : impl->channels)
    impl->channel_datasets.push_back(
        impl->cut_dataset(channel.path, channel.n_components, reopen.rows));
  impl->n_rows_written = reopen.rows;
}

HistoryWriter::~HistoryWriter()
{
  if (!impl)
    return;
  // After a failed write (a full disk), or while an error unwinds the run, the file is let go
  // as its last flush left it: closing would flush the metadata of rows that may not fit, and
  // HDF5 goes on past a failed write and leaves a file it cannot open again. A destructor
  // cannot throw: on the normal path it reports a failure to close and goes on.
  if (impl->failed || std::uncaught_exceptions() > 0)
  {
    abandon();
    return;
  }
  try
  {
    impl->write_buffered_rows();
  }
  catch (const std::exception& error)
  {
    std::cerr << "HistoryWriter: " << error.what() << ": last rows lost\n";
    abandon();
    return;
  }
  impl->time_dataset.reset();
  impl->channel_datasets.clear();
  if (!impl->file.reset())
    std::cerr << "HistoryWriter: cannot close HDF5 history file '" << impl->filename << "'\n";
}

void HistoryWriter::abandon() noexcept
{
  // The identifiers are dropped without closing them (HDF5 does not clean up at exit: see the
  // constructor), so nothing more reaches the file; the process's exit closes its descriptor.
  impl->time_dataset.release();
  for (Handle& dataset : impl->channel_datasets)
    dataset.release();
  impl->file.release();
  H5Eclear2(H5E_DEFAULT);
}

void HistoryWriter::append(double time, const std::vector<double>& values)
{
  if (values.size() != impl->n_values_per_row)
    throw std::invalid_argument("HistoryWriter '" + impl->filename + "': append() got " +
                                std::to_string(values.size()) + " values, expected " +
                                std::to_string(impl->n_values_per_row) +
                                " (sum of the channels' n_components)");
  impl->time_buffer.push_back(time);
  auto value = values.begin();
  for (std::size_t c = 0; c < impl->channels.size(); ++c)
  {
    const auto n = static_cast<std::ptrdiff_t>(impl->channels[c].n_components);
    impl->buffers[c].insert(impl->buffers[c].end(), value, value + n);
    value += n;
  }
  if (impl->time_buffer.size() >= impl->flush_every)
    impl->write_buffered_rows();
}

void HistoryWriter::flush()
{
  impl->write_buffered_rows();
  impl->throw_if_failed();
  impl->require_space();
  if (H5Fflush(impl->file.get(), H5F_SCOPE_GLOBAL) < 0)
  {
    impl->failed = true;
    throw_hdf5_error(impl->filename, "", "flush the file to disk (is the disk full?)");
  }
}

void HistoryWriter::set_attribute(const std::string& name, const std::string& value)
{
  impl->write_string_attribute(impl->file.get(), "/", name, value);
}

std::size_t HistoryWriter::n_rows() const
{
  return impl->n_rows_written + impl->time_buffer.size();
}

} // namespace ddafem
