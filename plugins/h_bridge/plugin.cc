// SPDX-License-Identifier: GPL-3.0-or-later
#include "h_bridge.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::HBridge)
