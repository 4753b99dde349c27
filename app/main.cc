// ddafem command line: check and run scenes.
//
//   ddafem check SCENE [--set key=value]...
//   ddafem run SCENE [-o DIR] [--quiet] [--set key=value]...
//   ddafem scene-reference
//
// Exit codes: 0 success, 1 numerical failure (or an I/O failure while writing results),
// 2 bad input (scene, command line, missing file).
#include "app/run.h"
#include "app/scene.h"
#include "common/input_error.h"

#include <iostream>
#include <string>
#include <vector>

namespace
{
const char* usage = R"(usage:
  ddafem check SCENE [--set key=value]...             validate a scene and print a model summary
  ddafem run SCENE [-o DIR] [--quiet] [--allow-unstable] [--set key=value]...
                                                      run a scene, results into DIR
  ddafem scene-reference                              print the scene key reference (Markdown)
  ddafem --version | --help

  --set path.to.key=value   override any scene key, e.g. --set time.dt=1e-4
  -o DIR                    output directory (default: the scene's output.directory)
  --quiet                   no progress line
  --allow-unstable          run although a boundary feeds energy in at this dt (it will fail)
exit codes: 0 success, 1 numerical failure, 2 bad input
)";

struct CommandLine
{
  std::string command;
  std::string scene;
  std::string output_directory;
  bool quiet = false;
  bool allow_unstable = false;
  std::vector<ddafem::Override> overrides;
};

CommandLine parse_command_line(int argc, char** argv)
{
  CommandLine cl;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty())
    throw ddafem::InputError(std::string("no command given\n") + usage);
  cl.command = args[0];
  for (std::size_t i = 1; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    const auto next = [&]() -> const std::string&
    {
      if (i + 1 >= args.size())
        throw ddafem::InputError("option '" + a + "' expects a value");
      return args[++i];
    };
    if (a == "--set")
      cl.overrides.push_back(ddafem::parse_override(next()));
    else if (a.rfind("--set=", 0) == 0)
      cl.overrides.push_back(ddafem::parse_override(a.substr(6)));
    else if (a == "-o" || a == "--output")
      cl.output_directory = next();
    else if (a == "--quiet" || a == "-q")
      cl.quiet = true;
    else if (a == "--allow-unstable")
      cl.allow_unstable = true;
    else if (!a.empty() && a[0] == '-')
      throw ddafem::InputError("unknown option '" + a + "'\n" + usage);
    else if (cl.scene.empty())
      cl.scene = a;
    else
      throw ddafem::InputError("unexpected argument '" + a + "': only one scene file is taken");
  }
  return cl;
}
} // namespace

int main(int argc, char** argv)
{
  try
  {
    const CommandLine cl = parse_command_line(argc, argv);
    if (cl.command == "--help" || cl.command == "-h" || cl.command == "help")
    {
      std::cout << usage;
      return 0;
    }
    if (cl.command == "--version")
    {
      std::cout << "ddafem " << DDAFEM_VERSION << "\n";
      return 0;
    }
    if (cl.command == "scene-reference")
    {
      std::cout << ddafem::scene_reference_markdown();
      return 0;
    }
    if (cl.command != "check" && cl.command != "run")
      throw ddafem::InputError("unknown command '" + cl.command + "'\n" + usage);
    if (cl.scene.empty())
      throw ddafem::InputError("'" + cl.command + "' expects a scene file\n" + usage);

    const ddafem::Scene scene = ddafem::read_scene(cl.scene, cl.overrides);
    try
    {
      if (cl.command == "check")
      {
        std::cout << ddafem::check_scene(scene);
        return 0;
      }
      ddafem::RunOptions options;
      options.output_directory = cl.output_directory;
      options.quiet = cl.quiet;
      options.allow_unstable = cl.allow_unstable;
      return ddafem::run_scene(scene, options, std::cout);
    }
    catch (const ddafem::InputError& e)
    {
      // Problems only the engine sees (e.g. blocks sharing an edge without a joint material).
      throw ddafem::InputError(scene.file + ": " + e.what());
    }
  }
  catch (const ddafem::InputError& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
