// Files compiled into the luz binary for the built-in scenes (demo:NAME), so that a demo finds
// its mesh wherever luz runs from.
#pragma once

#include <optional>
#include <string_view>

namespace luz {

/// The text of the embedded file `name` (e.g. "bunny.obj", from scenes/), or nullopt.
std::optional<std::string_view> embedded_file(std::string_view name);

}  // namespace luz
