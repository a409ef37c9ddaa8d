// SPDX-License-Identifier: GPL-3.0-or-later
#include "logger.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::Logger)
