// SPDX-License-Identifier: GPL-3.0-or-later
#include "imu.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::Imu)
