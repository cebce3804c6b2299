package io.dtron.models.robotarm;

import io.dtron.testsupport.ShellWords;
import java.io.IOException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

/** The robot arm's Java plant ({@link RobotArmPlant}) in a JVM of its own, and the control page's lines for it. */
final class ArmProcess {
    /** The checkout's folder, from which the page's paths are. */
    static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    /** How the page starts the arm, its options following. */
    static final String PAGE_PREFIX = "$ java -cp models/target/classes:dtron-cli/target/dtron.jar "
            + RobotArmPlant.class.getName() + " ";

    private ArmProcess() {
    }

    /** Starts the arm with {@code args} (its options) on the test's class path, its output to {@code log}. */
    static Process start(List<String> args, Path log) throws IOException {
        String java = ProcessHandle.current().info().command().orElse(Path.of(System.getProperty("java.home"), "bin",
                "java").toString());
        String classPath = System.getProperty("surefire.test.class.path", System.getProperty("java.class.path"));
        List<String> command = new ArrayList<>(List.of(java, "-cp", classPath, RobotArmPlant.class.getName()));
        command.addAll(args);
        return new ProcessBuilder(command).redirectErrorStream(true).redirectOutput(log.toFile()).start();
    }

    /** The words of a command line of the page, on the bus {@code cluster} instead of 'arm', its paths absolute. */
    static List<String> args(String line, String cluster) {
        List<String> args = new ArrayList<>(ShellWords.split(line));
        for (int a = 0; a < args.size(); a++) {
            String word = args.get(a);
            if (word.equals("arm") && a > 0 && args.get(a - 1).equals("--cluster")) {
                args.set(a, cluster);
            } else if (word.startsWith("models/")) {
                args.set(a, ROOT.resolve(word).toString());
            }
        }
        return args;
    }
}
