"""The participant's way through a study: the step plan, the progress state machine, and the operations
behind the participant REST API (join, consent, instructions, questionnaires, completion)."""
