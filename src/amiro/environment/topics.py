"""Bus topics of the smart environment (the MQTT bridge maps them to the contract's topics)."""

SENSORS_TOPIC = "/amiro/env/sensors"
NOTIFICATIONS_TOPIC = "/amiro/notifications"
HEALTH_TOPIC = "/amiro/env/health"
DEVICE_COMMAND_TOPIC = "/amiro/env/devices/set"
DEVICE_STATE_TOPIC = "/amiro/env/devices/state"
