// The command line reads its JSON files with the server's reader (server/json_input.h).
#pragma once

#include "server/json_input.h"

namespace snooker::cli {

using server::FindInAnyCase;
using server::FindJsonSyntaxError;
using server::JsonSyntaxError;
using server::ReadJsonMessage;
using server::ValueList;

}  // namespace snooker::cli
