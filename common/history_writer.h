// Time histories in HDF5: one extendible dataset per channel, rows appended as the run goes.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace ddafem
{
/// One named series: a dataset of n_rows x n_components doubles (1 component: a 1D dataset).
struct HistoryChannel
{
  std::string path;         ///< dataset path inside the file, e.g. "monitors/M1/stress"
  std::size_t n_components; ///< values per row, >= 1
  std::string unit;         ///< stored as the dataset's "unit" attribute, e.g. "Pa"
  std::string description;  ///< stored as the "description" attribute, e.g. "(sxx, syy, sxy),
                            ///< tension positive"
};

/// Writes /time (1D, unit s) and one dataset per channel. Rows are buffered in memory and
/// written every `flush_every` rows, on flush() and on destruction, so that a run that stops
/// early (numerical failure) still leaves a readable file with every row appended so far.
/// Datasets are chunked and extendible (unlimited rows) and carry the string attributes "unit"
/// and "description"; intermediate groups ("monitors/M1") are created as needed.
/// I/O failures throw std::runtime_error naming the file and the dataset; misuse (no channel
/// path, n_components == 0, flush_every == 0, wrong number of values) throws
/// std::invalid_argument. The destructor writes the last rows and cannot throw: it prints a
/// failure to std::cerr, so call flush() at the end of a run to get errors as exceptions.
/// The file is opened for writing (and locked by HDF5) until the writer is destroyed.
///
/// Crash safety: flush() leaves a file that HDF5 opens again, whatever happens afterwards
/// (kill -9, a full disk). Before each write the free space of the file's disk is checked
/// against what the write can need; on too little, or after any failed write, nothing more is
/// written and the file keeps its last flush. A writer destroyed while an exception unwinds
/// does not flush either (the run is failing; its disk may be full).
class HistoryWriter
{
public:
  HistoryWriter(const std::string& filename, std::vector<HistoryChannel> channels,
                std::size_t flush_every = 256);
  /// Reopens a file such a writer wrote, with the same channels (a resumed run): every dataset
  /// is cut back to its first `rows` rows, and appends go on after them. Throws
  /// std::runtime_error naming the file and dataset if one is missing or shorter.
  struct Reopen
  {
    std::size_t rows = 0;
  };
  HistoryWriter(const std::string& filename, std::vector<HistoryChannel> channels, Reopen reopen,
                std::size_t flush_every = 256);
  ~HistoryWriter();
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  /// Appends one row: time [s] and the channels' values concatenated in channel order
  /// (values.size() == sum of n_components).
  void append(double time, const std::vector<double>& values);

  /// Writes buffered rows and flushes the file to disk.
  void flush();

  /// Writes a string attribute on the root group (scene name, version, ...).
  void set_attribute(const std::string& name, const std::string& value);

  std::size_t n_rows() const;

private:
  /// Lets the file go without flushing or closing it (after a failed write, or an error).
  void abandon() noexcept;

  struct Impl;
  std::unique_ptr<Impl> impl;
};

} // namespace ddafem
