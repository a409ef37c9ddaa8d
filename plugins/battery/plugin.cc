// SPDX-License-Identifier: GPL-3.0-or-later
#include "battery.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::Battery)
