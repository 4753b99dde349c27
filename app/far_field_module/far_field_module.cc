#include "app/far_field_module/far_field_module.h"

#include "common/input_error.h"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

// Weak: null unless the module's objects are linked into this program (the test programs).
extern "C" const ddafem::FarFieldModule* ddafem_far_field_module() __attribute__((weak));

namespace ddafem
{
namespace
{
/// libddafem_far_field.so beside the executable.
std::filesystem::path module_file()
{
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  return exe.parent_path() / "libddafem_far_field.so";
}
} // namespace

const FarFieldModule& far_field_module()
{
  if (ddafem_far_field_module)
    return *ddafem_far_field_module();
  const std::filesystem::path file = module_file();
  // dlopen counts references: after the first call this returns the loaded module.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  const char* why = handle ? nullptr : dlerror();
  using Entry = const FarFieldModule* (*)();
  const auto entry =
      handle ? reinterpret_cast<Entry>(dlsym(handle, "ddafem_far_field_module")) : nullptr;
  if (!entry)
    throw InputError("far_field: a scene with a far field needs the module " + file.string() +
                     ", which could not be loaded (" +
                     (why ? std::string(why) : "no entry point ddafem_far_field_module") +
                     "): expected the libddafem_far_field.so built beside ddafem");
  return *entry();
}

void end_every_rank_after_error(const int exit_code)
{
  if (ddafem_far_field_module)
  {
    ddafem_far_field_module()->end_every_rank_after_error(exit_code);
    return;
  }
  // RTLD_NOLOAD: the module only if a scene has loaded it already.
  void* handle = dlopen(module_file().c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD);
  if (handle)
    far_field_module().end_every_rank_after_error(exit_code);
}

} // namespace ddafem
