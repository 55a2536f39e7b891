// placeholder until the certifier lands (issue 3)
namespace igm::certify { int placeholder() { return 0; } }
