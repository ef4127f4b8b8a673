"""The explainers as tools, from one list: LangGraph tools for the agent, and the MCP server (`hexar mcp`)."""
