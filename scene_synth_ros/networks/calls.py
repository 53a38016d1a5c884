"""The four network calls synthesis makes, whichever runtime answers them
(``runtime.OnnxCalls``, ``graphs.TorchCalls``)."""

# The network calls of synthesis: what each takes and gives, batch first.
#   category     (image, counts)    -> (logits,)            next category or STOP
#   location     (image,)           -> (logits, offsets)    offsets None without them
#   orientation  (crops, cats, z)   -> (outputs, snap logits)
#   dimensions   (crops, cats, z)   -> (log footprints,)
# Images are float32 (N, C, H, W), laid out channels-last where drawn so; cats int64;
# counts and z float32.
MODULE_CALLS = ('category', 'location', 'orientation', 'dimensions')

# The networks each call runs: their weights name its graph in the cache.
CALL_NETWORKS = {'category': ('category',), 'location': ('location',),
                 'orientation': ('orientation', 'snap'), 'dimensions': ('dimensions',)}
