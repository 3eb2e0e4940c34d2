"""Bus topics of the smart environment (the MQTT bridge maps them to the contract's topics)."""

SENSORS_TOPIC = "/amiro/env/sensors"
NOTIFICATIONS_TOPIC = "/amiro/notifications"
