"""Conversations kept bounded: each thread keeps only its latest checkpoint, and a conversation file keeps only
recent threads.

LangGraph saves a checkpoint per step of every answer, each with the whole state, so a thread of n questions
holds about 5n checkpoints of growing size; a page that is asked 400 questions a second (or a node flooded on
/hexar/question) grows without end. The agent needs only the latest checkpoint of a thread to go on with it.
"""

from __future__ import annotations

import sqlite3
import time
from typing import Any

from langgraph.checkpoint.memory import InMemorySaver
from langgraph.checkpoint.sqlite import SqliteSaver

MAX_THREADS = 500
"""Threads a conversation file keeps; the least recently used go first."""
MAX_AGE_S = 30 * 24 * 3600.0
"""A thread nobody continued for this long is deleted."""


def keep_latest(saver: Any, thread_id: str) -> None:
    """Delete every checkpoint of `thread_id` but its latest, with the writes and values only they used."""
    if isinstance(saver, SqliteSaver):
        with saver.cursor() as cur:
            latest = "(SELECT MAX(checkpoint_id) FROM checkpoints WHERE thread_id = ?)"
            cur.execute(f"DELETE FROM checkpoints WHERE thread_id = ? AND checkpoint_id <> {latest}",
                        (thread_id, thread_id))
            cur.execute(f"DELETE FROM writes WHERE thread_id = ? AND checkpoint_id <> {latest}",
                        (thread_id, thread_id))
    elif isinstance(saver, InMemorySaver):
        for ns, checkpoints in saver.storage.get(thread_id, {}).items():
            if not checkpoints:
                continue
            last = max(checkpoints)  # ids are time-ordered UUIDs (uuid6)
            kept = saver.serde.loads_typed(checkpoints[last][0])
            for old in [k for k in checkpoints if k != last]:
                del checkpoints[old]
            versions = set(kept.get("channel_versions", {}).items())
            for wkey in [k for k in saver.writes if k[0] == thread_id and k[1] == ns and k[2] != last]:
                del saver.writes[wkey]
            for bkey in [k for k in saver.blobs if k[0] == thread_id and k[1] == ns and (k[2], k[3]) not in versions]:
                del saver.blobs[bkey]


class ThreadBook:
    """When each thread of a conversation file was last used, and the pruning of old ones."""

    def __init__(self, conn: sqlite3.Connection, saver: Any) -> None:
        self.conn, self.saver = conn, saver
        with conn:
            conn.execute("CREATE TABLE IF NOT EXISTS hexar_threads (thread_id TEXT PRIMARY KEY, used REAL)")

    def used(self, thread_id: str) -> None:
        """Record a use of `thread_id` and delete the threads over the limits (never this one)."""
        now = time.time()
        with self.conn:
            self.conn.execute("INSERT OR REPLACE INTO hexar_threads VALUES (?, ?)", (thread_id, now))
            rows = self.conn.execute("SELECT thread_id, used FROM hexar_threads ORDER BY used DESC").fetchall()
        old = [t for i, (t, used) in enumerate(rows)
               if t != thread_id and (i >= MAX_THREADS or used < now - MAX_AGE_S)]
        for t in old:
            self.saver.delete_thread(t)
        if old:
            with self.conn:
                self.conn.executemany("DELETE FROM hexar_threads WHERE thread_id = ?", [(t,) for t in old])
