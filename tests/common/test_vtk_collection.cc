// The one VTK collection (.pvd) writer in the three spellings its series use.
#include "common/vtk_collection.h"

#include <gtest/gtest.h>

using namespace ddafem;

namespace
{
/// Two times of a two-part model: 0 and 0.1 + 0.2 = 0.30000000000000004 (not 0.3 in binary).
std::vector<CollectionDataSet> two_times()
{
  return {{0.0, 0, "blocks_00000.vtu"},
          {0.0, 1, "contacts_00000.vtu"},
          {0.1 + 0.2, 0, "blocks_00001.vtu"},
          {0.1 + 0.2, 1, "a&b\".vtu"}};
}
} // namespace

TEST(VtkCollection, ShortestTimesByDefault)
{
  EXPECT_EQ(collection_text(two_times()),
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"blocks_00000.vtu\"/>\n"
            "    <DataSet timestep=\"0\" group=\"\" part=\"1\" file=\"contacts_00000.vtu\"/>\n"
            "    <DataSet timestep=\"0.30000000000000004\" group=\"\" part=\"0\" "
            "file=\"blocks_00001.vtu\"/>\n"
            "    <DataSet timestep=\"0.30000000000000004\" group=\"\" part=\"1\" "
            "file=\"a&amp;b&quot;.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
}

TEST(VtkCollection, FixedDigitsCommentAndAttributeName)
{
  CollectionStyle style;
  style.time_precision = 12;
  style.comment = "#made by hand";
  style.byte_order_attribute = "ByteOrder";
  const std::vector<CollectionDataSet> one = {{0.1 + 0.2, 0, "far_field_00001.vtu"}};
  EXPECT_EQ(collection_text(one, style),
            "<?xml version=\"1.0\"?>\n"
            "<!--\n#made by hand\n-->\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" ByteOrder=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0.3\" group=\"\" part=\"0\" file=\"far_field_00001.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
  style.time_precision = 17;
  EXPECT_NE(collection_text(one, style).find("timestep=\"0.30000000000000004\""),
            std::string::npos);
}
