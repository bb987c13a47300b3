"""The live display of a drilling run (``drillstring live``): a session of the drilling system
stepped in real time (:mod:`.driver`), served with its page over HTTP and a WebSocket
(:mod:`.server`), what the page shows and in which units (:mod:`.display`); the page itself
(``static/``) draws the tracks and the along-string views with the vendored dygraphs library."""
