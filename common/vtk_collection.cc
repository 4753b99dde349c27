#include "common/vtk_collection.h"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace ddafem
{
namespace
{
/// `time` [s] as CollectionStyle::time_precision asks.
std::string time_text(double time, int precision)
{
  char buffer[48];
  if (precision == 0)
  {
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), time);
    return std::string(buffer, result.ptr);
  }
  std::snprintf(buffer, sizeof(buffer), "%.*g", precision, time);
  return buffer;
}
} // namespace

std::string collection_text(const std::vector<CollectionDataSet>& data_sets,
                            const CollectionStyle& style)
{
  std::string out = "<?xml version=\"1.0\"?>\n";
  if (!style.comment.empty())
    out += "<!--\n" + style.comment + "\n-->\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" " + style.byte_order_attribute +
         "=\"LittleEndian\">\n"
         "  <Collection>\n";
  for (const CollectionDataSet& d : data_sets)
    out += "    <DataSet timestep=\"" + time_text(d.time, style.time_precision) +
           "\" group=\"\" part=\"" + std::to_string(d.part) + "\" file=\"" + xml_escape(d.file) +
           "\"/>\n";
  out += "  </Collection>\n"
         "</VTKFile>\n";
  return out;
}

void write_collection(const std::filesystem::path& path,
                      const std::vector<CollectionDataSet>& data_sets, const CollectionStyle& style)
{
  write_file_atomically(path, collection_text(data_sets, style));
}

std::string xml_escape(const std::string& text)
{
  std::string escaped;
  for (const char c : text)
  {
    switch (c)
    {
    case '&':
      escaped += "&amp;";
      break;
    case '<':
      escaped += "&lt;";
      break;
    case '>':
      escaped += "&gt;";
      break;
    case '"':
      escaped += "&quot;";
      break;
    default:
      escaped += c;
    }
  }
  return escaped;
}

void write_file_atomically(const std::filesystem::path& path, const std::string& content)
{
  namespace fs = std::filesystem;
  fs::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out)
      throw std::runtime_error("cannot write '" + path.string() + "': cannot open '" +
                               temporary.string() + "' for writing");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out)
    {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw std::runtime_error("cannot write '" + path.string() + "' (through '" +
                               temporary.string() + "'; is the disk full?)");
    }
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error)
  {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot rename '" + temporary.string() + "' to '" + path.string() +
                             "': " + error.message());
  }
}

} // namespace ddafem
