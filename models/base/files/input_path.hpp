#pragma once
#include <string>

namespace aesim {

// What a path from a user names, asked without exceptions from std::filesystem: a name the system
// cannot look up at all (a component too long, a file used as a folder, no permission) is an
// InputError naming `what`, the path and the system's reason; a name that does not exist is
// simply neither a file nor a folder.
bool is_input_file(const std::string& path, const std::string& what);
bool is_input_folder(const std::string& path, const std::string& what);

// What a path is when it is not a regular file, in words for a message: "not found", "is a folder,
// not a file", "is a FIFO, not a file", "is a character device, not a file", ...
std::string not_a_file(const std::string& path);
// InputError "WHAT 'PATH': is a FIFO, not a file" (or not found, ...) unless it is a regular file.
void require_input_file(const std::string& path, const std::string& what);

// The extension a file's format is told by, in lower case ("" for none): a camera's IMG_0001.JPG is
// a JPEG, a recording's RUN.AEDAT4 an AEDAT 4.0 file.
std::string file_extension(const std::string& path);

}  // namespace aesim
