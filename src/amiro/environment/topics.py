"""Bus topics of the smart environment (the MQTT bridge maps them to the contract's topics)."""
