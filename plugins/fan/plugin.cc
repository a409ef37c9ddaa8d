// SPDX-License-Identifier: GPL-3.0-or-later
#include "fan.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::Fan)
