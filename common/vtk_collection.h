// The VTK collection (.pvd) that gathers time series of VTU files for ParaView, one writer for
// the blocks' and contacts' series (dda/vtu_writer.cc), the far field's (fem/far_field_output.cc)
// and a run's model.pvd (app/run/run_outputs.cc); and the atomic file write they share.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace ddafem
{
/// One file of a collection.
struct CollectionDataSet
{
  double time = 0.0; ///< simulated time [s]
  unsigned part = 0; ///< parts of one time are shown together (blocks, contacts, far field, ties)
  std::string file;  ///< VTU file name relative to the .pvd
};

/// How a collection spells its times and header. Each series keeps the spelling it had before
/// the writers became one, so that every .pvd stays byte for byte what it was.
struct CollectionStyle
{
  /// Significant digits of the times (printf's %g); 0: the shortest decimal text that reads back
  /// as exactly the same double (std::to_chars).
  int time_precision = 0;
  /// Text of an XML comment after the declaration, on its own lines; empty: none.
  std::string comment;
  /// Name of the byte-order attribute (VTK reads "byte_order"; deal.II writes "ByteOrder").
  std::string byte_order_attribute = "byte_order";
};

/// The .pvd text: the XML declaration, the comment, and one <DataSet> per entry in order, its
/// file name escaped for an XML attribute.
std::string collection_text(const std::vector<CollectionDataSet>& data_sets,
                            const CollectionStyle& style = {});

/// Writes collection_text to `path` atomically (write_file_atomically).
void write_collection(const std::filesystem::path& path,
                      const std::vector<CollectionDataSet>& data_sets,
                      const CollectionStyle& style = {});

/// Escapes the characters that cannot appear literally in an XML attribute value.
std::string xml_escape(const std::string& text);

/// Writes `content` to PATH.tmp and renames it to `path`, so that readers never see a
/// half-written file. Throws std::runtime_error naming the path on failure.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

} // namespace ddafem
