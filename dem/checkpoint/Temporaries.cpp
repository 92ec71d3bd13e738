#include "dem/checkpoint/Temporaries.h"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <optional>
#include <system_error>

namespace talus::dem::checkpoint
{
namespace
{
std::atomic<unsigned> saveCounter{0};

std::string hostName()
{
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0)
    return "unknown-host";
  return name.data();
}

bool allDigits(const std::string& text)
{
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}

/// The writer of a temporary file named `name`: its pid and host ("" for the names without a
/// host); nothing if `name` is not a temporary file name.
struct Writer
{
  long pid;
  std::string host;
};
std::optional<Writer> writerOf(const std::string& name)
{
  const std::size_t tag = name.rfind(".tmp-");
  if (name.size() < 2 || name[0] != '.' || tag == std::string::npos || tag < 2)
    return std::nullopt;
  std::string rest = name.substr(tag + 5), host;
  if (const std::size_t at = rest.find('@'); at != std::string::npos)
  {
    host = rest.substr(at + 1);
    rest.resize(at);
    if (host.empty())
      return std::nullopt;
  }
  const std::size_t dash = rest.find('-');
  if (dash == std::string::npos || dash > 9 || !allDigits(rest.substr(0, dash)) || !allDigits(rest.substr(dash + 1)))
    return std::nullopt; // (a pid has at most 7 digits: 9 keeps strtol in range)
  return Writer{std::strtol(rest.substr(0, dash).c_str(), nullptr, 10), host};
}

/// No process with this id runs here (EPERM: one runs, owned by someone else).
bool dead(long pid)
{
  return pid > 0 && pid != static_cast<long>(::getpid()) && ::kill(static_cast<pid_t>(pid), 0) != 0
         && errno == ESRCH;
}
} // namespace

std::string temporaryPath(const std::filesystem::path& folder, const std::filesystem::path& target)
{
  // Appended piece by piece: GCC 12 takes `"literal" + string` here for an overlapping copy.
  std::string name = ".";
  for (const std::string& piece : {target.filename().string(), std::string(".tmp-"), std::to_string(::getpid()),
                                   std::string("-"), std::to_string(saveCounter++), std::string("@"), hostName()})
    name += piece;
  return (folder / name).string();
}

void removeStaleTemporaries(const std::filesystem::path& folder)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::directory_iterator it(folder, ec);
  if (ec)
    return;
  const std::string here = hostName();
  for (const fs::directory_entry& entry : it)
  {
    const std::optional<Writer> writer = writerOf(entry.path().filename().string());
    if (writer && (writer->host.empty() || writer->host == here) && dead(writer->pid)
        && entry.is_regular_file(ec))
      fs::remove(entry.path(), ec);
  }
}
} // namespace talus::dem::checkpoint
