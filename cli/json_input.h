// The command line reads its JSON files with the server's reader (server/json_input.h).
#pragma once

#include "server/json_input.h"

namespace snooker::cli {

using server::FindJsonSyntaxError;
using server::JsonSyntaxError;
using server::ReadJsonMessage;

}  // namespace snooker::cli
