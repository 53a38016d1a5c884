print("x")
def main(): print("hi")
