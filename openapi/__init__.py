"""The committed OpenAPI document of the service and the script that generates it."""
