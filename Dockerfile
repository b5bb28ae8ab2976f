# The study server image (see docs/deploy.md).
#   docker build -t steakhouse .
#   docker run -p 8000:8000 -v steakhouse-data:/app/data -e STEAKHOUSE_ADMIN_TOKEN=... steakhouse
# PostgreSQL instead of the SQLite file in /app/data:
#   docker run -p 8000:8000 -e DATABASE_URL=postgresql://user:pass@db:5432/steakhouse steakhouse
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1

WORKDIR /app

# Dependencies and the package first (cached while only the client changes).
COPY pyproject.toml README.m[d] ./
COPY planner ./planner
COPY server ./server
COPY store ./store
COPY analysis ./analysis
COPY study_config ./study_config
RUN pip install . \
    && useradd --create-home --uid 1000 steakhouse \
    && mkdir -p /app/data \
    && chown steakhouse /app/data

# The browser client, served at / when the folder has files.
COPY static ./static

USER steakhouse
EXPOSE 8000
VOLUME ["/app/data"]
HEALTHCHECK --interval=30s --timeout=5s --start-period=20s \
    CMD python -c "import sys, urllib.request; sys.exit(urllib.request.urlopen('http://127.0.0.1:8000/healthz', timeout=4).status != 200)"

# SQLite file ./data/steakhouse.sqlite3 by default; DATABASE_URL (or STEAKHOUSE_DATABASE_URL) for PostgreSQL.
CMD ["steakhouse", "serve", "--host", "0.0.0.0", "--port", "8000"]
