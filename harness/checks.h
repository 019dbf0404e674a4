// Checks made before any work, shared by the commands and the runners (check, sweep):
// bad input stops a command before it prints or writes anything.
#pragma once

#include <string>
#include <vector>

#include "harness/settings.h"

namespace sb {

struct RenderCache;  // harness/render.h

// `s` as one shell word: as it is when it holds only safe characters, else in
// single quotes (a command line printed for the user to run).
std::string shellQuoted(const std::string& s);
// Checks made before any work, so that bad input stops a command before it
// prints or writes anything; each throws InputError naming `option` and the path.
// An output file: its extension is one of `extensions` (".png"), its folder
// exists and is writable, and it is not a folder itself.
void checkOutputPath(const std::string& option, const std::string& path,
                     const std::vector<std::string>& extensions);
// An output folder made when first needed: the folder, or its nearest existing
// parent, is a writable folder (nothing is created).
void checkOutputFolder(const std::string& option, const std::string& path);
// Everything a render request names, without rendering: every setting's range
// (checkRequest), the scene (built, and kept in `cache` when given), the
// techniques and the view; with `device`, the backend's device is created once.
// Messages name the setting as `spelling` spells it ("--shadow x: ...").
void checkRenderRequest(const RenderRequest& req, bool device, RenderCache* cache = nullptr,
                        Spelling spelling = Spelling::Cli);
}  // namespace sb
