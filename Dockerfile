# flexwing: the FastAPI service over the solver. Same steps as the README's "Run it" section.
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1 \
    OPENBLAS_NUM_THREADS=1

# The solver compiles its CasADi functions to C once per mesh size: it needs a C compiler
# (without one it still works, on CasADi's slower virtual machine).
RUN apt-get update \
    && apt-get install -y --no-install-recommends gcc libc6-dev \
    && rm -rf /var/lib/apt/lists/*

RUN useradd --create-home --uid 10001 flexwing
WORKDIR /opt/flexwing
COPY pyproject.toml README.md ./
COPY solver ./solver
COPY app ./app
RUN pip install .

USER flexwing
ENV FLEXWING_CACHE_DIR=/home/flexwing/.cache/flexwing
# Compile the common mesh size into the image, so workers start warm in milliseconds. The
# library targets the build machine's x86-64 ISA level; a host without that level compiles its
# own at first use (the level is in the library's name, so it never loads this one).
RUN python -c "import solver; assert solver.warm_up(30), 'no compiled library for N = 30'"

EXPOSE 8000
HEALTHCHECK --interval=15s --timeout=3s --start-period=60s --retries=3 \
    CMD ["python", "-c", "import urllib.request; urllib.request.urlopen('http://127.0.0.1:8000/healthz', timeout=3)"]
# Idle keep-alive connections outlive common client expiries (httpx: 5 s), so a client never
# reuses a connection the server is closing at the same moment.
CMD ["uvicorn", "app.main:app", "--host", "0.0.0.0", "--port", "8000", "--timeout-keep-alive", "75"]
