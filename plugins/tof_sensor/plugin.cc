// SPDX-License-Identifier: GPL-3.0-or-later
#include "tof_sensor.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::TofSensor)
