/// @file
/// Forwarding header, kept for one release: owner-computes is the HA-buffer's
/// scheduling and lives in its technique folder (issue 47). Include
/// habuffer/techniques/ha/owner_computes.h.
#pragma once

#include "habuffer/techniques/ha/owner_computes.h"
