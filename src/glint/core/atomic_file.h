#pragma once
/// Writing files so that readers see the old content or the new, never a truncated mix.

#include <string>
#include <string_view>

namespace glint {

/// Writes `bytes` to a temporary file beside `path`, flushes it to disk, then renames it over
/// `path`. Throws RenderError naming the path and the system's reason on failure; the
/// temporary is removed and any existing `path` is left untouched.
void writeFileAtomically(const std::string& path, std::string_view bytes);

/// The temporary file a writeFileAtomically call is writing right now, or null. For signal
/// handlers that must leave at once: reading it and unlink() are async-signal-safe.
const char* pendingTempFile();

}  // namespace glint
