// SPDX-License-Identifier: GPL-3.0-or-later
#include "bundled_components.h"

#include "battery.h"
#include "dc_motor.h"
#include "encoder.h"
#include "h_bridge.h"
#include "link.h"
#include "logger.h"
#include "tof_sensor.h"

namespace unimouse {

void AddBundledComponents(PluginRegistry& registry) {
  registry.AddStatic(ComponentType<plugins::Battery>());
  registry.AddStatic(ComponentType<plugins::HBridge>());
  registry.AddStatic(ComponentType<plugins::DcMotor>());
  registry.AddStatic(ComponentType<plugins::Encoder>());
  registry.AddStatic(ComponentType<plugins::TofSensor>());
  registry.AddStatic(ComponentType<plugins::Logger>());
  registry.AddStatic(ComponentType<link::Link>());
}

}  // namespace unimouse
