// The temporary files of checkpoint saves (internal, not installed): a save writes beside its
// target under a name that says which process on which host writes it, then renames it; a
// process killed in between leaves it behind, and the next save or load in that folder removes
// it once that process is gone.
#pragma once

#include <filesystem>
#include <string>

namespace talus::dem::checkpoint
{
/// Where a save of `target` (in `folder`) writes before renaming:
/// `<folder>/.<target name>.tmp-<pid>-<n>@<host>`, n counting this process's saves.
/// @param folder the target's folder (the rename stays within one file system)
/// @param target the file saved to (only its name is used)
/// @return the temporary file's path, unique to this process and save
std::string temporaryPath(const std::filesystem::path& folder, const std::filesystem::path& target);

/// Remove the temporary files in `folder` whose writer is dead: written on this host (or
/// without a host: by a Talus before the host was part of the name) by a process that no
/// longer runs. Files of live processes, of other hosts (a folder shared over the network) and
/// every other file stay. Best effort: a folder that cannot be listed or a file that cannot be
/// removed is left as it is.
/// @param folder the folder looked in (not its subfolders)
void removeStaleTemporaries(const std::filesystem::path& folder);
} // namespace talus::dem::checkpoint
