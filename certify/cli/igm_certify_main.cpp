// placeholder until the certifier lands (issue 3)
int main() { return 2; }
