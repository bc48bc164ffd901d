// SPDX-License-Identifier: MIT
#pragma once
// A header that breaks the client SDK's header rule on purpose: the
// hygiene check must refuse it (client_header_hygiene_detects_leaks).
#include "rewind/net/connection.h"
