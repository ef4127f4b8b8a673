"""HEXAR live: listen to a running robot over DDS or rclpy, explain failures as they happen, answer questions."""

from __future__ import annotations
