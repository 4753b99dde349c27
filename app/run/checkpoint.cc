#include "app/run/checkpoint.h"

#include "common/checkpoint_archive.h"
#include "common/input_error.h"
#include "common/vtk_collection.h"

#include <boost/archive/archive_exception.hpp>

#include <fstream>
#include <iterator>

namespace ddafem
{
namespace
{
/// The first thing in a checkpoint: tells it from any other file.
const std::string magic = "ddafem checkpoint 1";

template <class Archive>
void transfer_header(Archive& a, CheckpointHeader& h)
{
  transfer_all(a, h.version, h.scene_file, h.scene_text, h.settings, h.allow_unstable);
}
} // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& dir)
{
  return dir / "checkpoint.bin";
}

std::string scene_file_text(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::size_t write_checkpoint(const std::filesystem::path& dir, const CheckpointHeader& header,
                             const Simulation& simulation)
{
  std::ostringstream text;
  {
    CheckpointOut out(text);
    std::string mark = magic;
    out << mark;
    transfer_header(out, const_cast<CheckpointHeader&>(header));
    simulation.save_checkpoint(out);
  }
  const std::string bytes = text.str();
  write_file_atomically(checkpoint_path(dir), bytes);
  return bytes.size();
}

CheckpointReader::CheckpointReader(const std::filesystem::path& dir) : path(checkpoint_path(dir))
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
    throw InputError(path.string() + ": no checkpoint to resume from: expected the output " +
                     "directory of a run killed or stopped after its first checkpoint (a run " +
                     "with output.checkpoint_every 0, or that ended, has none: run the scene " +
                     "again)");
  text.str(std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()));
  try
  {
    in = std::make_unique<CheckpointIn>(text);
    std::string mark;
    *in >> mark;
    if (mark != magic)
      throw InputError(path.string() + ": not a ddafem checkpoint");
    transfer_header(*in, head);
  }
  catch (const boost::archive::archive_exception& e)
  {
    throw InputError(path.string() + ": not a readable ddafem checkpoint (" + e.what() + ")");
  }
  if (head.version != DDAFEM_VERSION)
    throw InputError(path.string() + ": written by ddafem " + head.version + ", this is ddafem " +
                     DDAFEM_VERSION +
                     ": expected the version that wrote it (or run the scene again)");
}

CheckpointReader::~CheckpointReader() = default;

} // namespace ddafem
