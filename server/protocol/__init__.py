"""The websocket protocol (version 1): typed messages both ways, sequence numbers, typed errors.

See ``docs/protocol.md`` for the prose description and examples.
"""

PROTOCOL_VERSION = 1
