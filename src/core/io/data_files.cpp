#include "rle_vision/io/data_files.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <vector>

namespace rle_vision {
namespace {

bool readable(const std::string& path) { return std::ifstream(path).good(); }

// The folder of the running executable ("" when unknown).
std::string executableDir() {
  std::vector<char> buffer(4096);
  const ssize_t n = readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n <= 0) return "";
  const std::string exe(buffer.data(), static_cast<size_t>(n));
  return exe.substr(0, exe.find_last_of('/'));
}

}  // namespace

std::string packageDataFile(const std::string& relative) {
  std::vector<std::string> roots;
  if (const char* dir = std::getenv("RLE_VISION_DATA_DIR")) roots.push_back(dir);
  const std::string exe_dir = executableDir();
  if (!exe_dir.empty()) {
    roots.push_back(exe_dir + "/../share/rle_vision");     // <prefix>/bin
    roots.push_back(exe_dir + "/../../share/rle_vision");  // <prefix>/lib/rle_vision (catkin)
  }
  roots.push_back(RLE_VISION_SOURCE_DIR);
  for (const std::string& root : roots) {
    const std::string path = root + "/" + relative;
    if (readable(path)) return path;
  }
  return "";
}

}  // namespace rle_vision
