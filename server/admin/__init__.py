"""What the admin API computes for the dashboard (kept out of the thin routes in ``server/routes/admin.py``):
full-kitchen scenes with the participant's field of view for the live view and replays, recruiting links,
questionnaire answers."""
