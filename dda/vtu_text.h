// The text of VTK XML UnstructuredGrid files (.vtu), ASCII, piece by piece: what
// VtuSeriesWriter (dda/vtu_writer.h) writes for the blocks and contacts, and what an element
// kind's outputs write for their own series (app/run/<element>_outputs.cc) through
// VtuSeriesWriter::write_text. Numbers are the shortest decimal text that reads back exactly.
#pragma once

#include "dda/types.h"

#include <charconv>
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

namespace ddafem::dda::vtu
{
/// VTK cell types (vtkCellType.h): a simple polygon, convex or not, and a single point.
inline constexpr int vtk_polygon = 7;
inline constexpr int vtk_vertex = 1;
inline constexpr int vtk_line = 3;
inline constexpr int vtk_poly_line = 4;

/// Appends the shortest decimal text that reads back as exactly `value` (std::to_chars).
inline void append_number(std::string& out, double value)
{
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

template <typename Integer>
inline void append_integer(std::string& out, Integer value)
{
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

/// Opens a cell-data DataArray element.
inline void open_array(std::string& out, const char* type, const char* name, int n_components)
{
  out += "        <DataArray type=\"";
  out += type;
  out += "\" Name=\"";
  out += name;
  out += '"';
  if (n_components > 1)
  {
    out += " NumberOfComponents=\"";
    append_integer(out, n_components);
    out += '"';
  }
  out += " format=\"ascii\">\n";
}

inline constexpr const char* close_array = "        </DataArray>\n";

/// Appends a 2D vector as a 3-component tuple with z = 0.
inline void append_vector(std::string& out, const Vector2& v)
{
  out += "          ";
  append_number(out, v[0]);
  out += ' ';
  append_number(out, v[1]);
  out += " 0\n";
}

/// The opening of a .vtu file up to the <Piece> element.
inline void open_piece(std::string& out, double time, std::size_t n_points, std::size_t n_cells)
{
  out += "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <UnstructuredGrid>\n"
         "    <FieldData>\n"
         "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
         "format=\"ascii\">";
  append_number(out, time);
  out += "</DataArray>\n"
         "    </FieldData>\n"
         "    <Piece NumberOfPoints=\"";
  append_integer(out, n_points);
  out += "\" NumberOfCells=\"";
  append_integer(out, n_cells);
  out += "\">\n";
}

/// One integer or number per line of a cell-data array, `get` of each item.
template <typename Value, typename Item>
inline void
append_column(std::string& out, const std::vector<Item>& items, const char* type, const char* name,
              Value (*get)(const typename std::vector<Item>::value_type&)) // get: not deduced
{
  open_array(out, type, name, 1);
  for (const Item& item : items)
  {
    out += "          ";
    if constexpr (std::is_floating_point_v<Value>)
      append_number(out, get(item));
    else
      append_integer(out, get(item));
    out += '\n';
  }
  out += close_array;
}

/// A 3-component cell-data array of 2D vectors (z = 0), `get` of each item.
template <typename Item>
inline void append_vector_column(std::string& out, const std::vector<Item>& items, const char* name,
                                 Vector2 (*get)(const Item&))
{
  open_array(out, "Float64", name, 3);
  for (const Item& item : items)
    append_vector(out, get(item));
  out += close_array;
}

inline constexpr const char* close_piece = "    </Piece>\n"
                                           "  </UnstructuredGrid>\n"
                                           "</VTKFile>\n";

} // namespace ddafem::dda::vtu
