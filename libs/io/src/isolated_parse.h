#pragma once
// Guards against MRPT's deserialiser on corrupted files (internal to gridtopo_io). MRPT 2.5.8 can crash
// (segmentation fault) on corrupted -- not truncated -- binary data, e.g. inside
// CActionRobotMovement2D::serializeFrom, or try to allocate gigabytes for a corrupted size field. A file is
// therefore parsed once in a child process before the real parse.
#include <cstdint>
#include <functional>
#include <string>

namespace gridtopo::io {

/// Runs parse() in a child process (fork) with a bounded address space (its size at the fork + 1 GiB + 64 times
/// the file's size), no core file and its output sent to /dev/null. parse() may set *entry to the index of the
/// object it is reading, which then locates the failure. Throws gridtopo::InputError naming `path` (and
/// "entry N" when parse() counts entries) if the child crashed ("MRPT's deserialiser crashed (<signal>) ..."),
/// ran out of its address space, or threw (the InputError's field and message, or "entry N" and what()).
/// Returns normally when parse() completed in the child, or when no child could be started (then the caller's
/// own parse is the only one, as without the guard).
void checkParsesInChild(const std::string& path, const std::function<void(volatile std::uint64_t* entry)>& parse);

/// The useful line of an MRPT exception text (the innermost "Message:"), unprintable bytes as '?'.
std::string innermostMrptMessage(const std::string& text);

}  // namespace gridtopo::io
