package io.dtron.troninstaller;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.charset.Charset;
import java.nio.file.Files;
import java.nio.file.InvalidPathException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.apache.commons.exec.CommandLine;
import org.apache.commons.exec.DefaultExecutor;
import org.apache.commons.exec.ExecuteException;
import org.apache.commons.exec.ExecuteWatchdog;
import org.apache.commons.exec.PumpStreamHandler;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Where Uppaal TRON is installed on this machine. The executable is {@code tron} on Linux and macOS and {@code
 * tron.exe} on Windows; it is looked for first in {@code $TRON_HOME/bin}, then in {@code $TRON_HOME} itself, then
 * in the folders of {@code PATH} in order. Files that are not executable are skipped. The environment and the
 * operating system's name are given to the constructor, so that the lookup can be tested.
 */
public final class TronInstallation {
    /** The environment variable naming TRON's installation folder. */
    public static final String TRON_HOME = "TRON_HOME";
    /** How long {@link #version} lets TRON run. */
    static final Duration VERSION_TIMEOUT = Duration.ofSeconds(10);

    private static final Logger LOG = LoggerFactory.getLogger(TronInstallation.class);
    private static final Pattern VERSION = Pattern.compile(
            "(\\d+\\.\\d+(?:\\.\\d+)*(?:[- ]?(?:alpha|beta|rc)[ -]?\\d*)?)", Pattern.CASE_INSENSITIVE);

    private final Map<String, String> env;
    private final boolean windows;

    /** This machine's installation: the process environment and {@code os.name}. */
    public TronInstallation() {
        this(System.getenv(), System.getProperty("os.name"));
    }

    /**
     * The installation seen through {@code env} on an operating system called {@code osName} (as in the {@code
     * os.name} system property: names starting with "Windows" mean Windows).
     */
    public TronInstallation(Map<String, String> env, String osName) {
        this.env = Map.copyOf(Objects.requireNonNull(env, "env"));
        this.windows = Objects.requireNonNull(osName, "osName").toLowerCase(Locale.ROOT).startsWith("windows");
    }

    /** The executable's file name on this operating system: {@code tron} or {@code tron.exe}. */
    public String executableName() {
        return windows ? "tron.exe" : "tron";
    }

    /** The executable, if TRON is installed where DTRON looks. */
    public Optional<Path> find() {
        for (Path candidate : candidates()) {
            if (isExecutable(candidate)) {
                return Optional.of(candidate);
            }
        }
        String home = variable(TRON_HOME);
        if (home != null && !home.isBlank()) {
            LOG.warn("{} is set to {}, but neither {} nor {} is an executable file", TRON_HOME, home,
                    Path.of(home, "bin", executableName()), Path.of(home, executableName()));
        }
        return Optional.empty();
    }

    /**
     * The executable.
     *
     * @throws TronNotFoundException when TRON is not installed where DTRON looks; its message says where DTRON
     *                               looked and what to do
     */
    public Path require() throws TronNotFoundException {
        Optional<Path> found = find();
        if (found.isPresent()) {
            return found.get();
        }
        throw new TronNotFoundException(notFoundMessage());
    }

    /** The message of {@link #require()}'s exception: where DTRON looked, why TRON is not bundled, what to do. */
    public String notFoundMessage() {
        String home = variable(TRON_HOME);
        String homePart = home == null || home.isBlank()
                ? TRON_HOME + " is not set"
                : "looked in " + Path.of(home, "bin") + " and " + home + " (" + TRON_HOME + ")";
        String name = executableName();
        return "Uppaal TRON was not found: no executable '" + name + "' (" + homePart + ", and not on PATH). "
                + "DTRON does not bundle TRON, because TRON's licence forbids redistribution. To use TRON as the "
                + "backend, download Uppaal TRON from the Uppaal web site (uppaal.org, under TRON), unpack it, and "
                + "set " + TRON_HOME + " to the folder that holds " + Path.of("bin", name) + " (or put that folder "
                + "on PATH). Without TRON, leave out --backend tron: DTRON's own engine needs no TRON.";
    }

    /**
     * TRON's version, as it prints it when asked for help ({@code tron -h}); TRON is given 10 seconds.
     *
     * @throws TronNotFoundException when TRON is not installed
     * @throws IOException           when TRON cannot be run or prints no version
     */
    public String version() throws TronNotFoundException, IOException {
        return version(require());
    }

    /**
     * The version that the executable prints for {@code -h} (its exit code does not matter). The version is the
     * first number like {@code 1.5} or {@code 1.4 beta 1} on the first line that mentions TRON or a version.
     *
     * @throws IOException when the executable cannot be run, runs longer than the timeout, or prints no version
     */
    public static String version(Path executable) throws IOException {
        ByteArrayOutputStream output = new ByteArrayOutputStream();
        ExecuteWatchdog watchdog = ExecuteWatchdog.builder().setTimeout(VERSION_TIMEOUT).get();
        DefaultExecutor executor = DefaultExecutor.builder()
                .setExecuteStreamHandler(new PumpStreamHandler(output)).get();
        executor.setWatchdog(watchdog);
        executor.setExitValues(null);
        CommandLine command = new CommandLine(executable.toFile()).addArgument("-h");
        try {
            executor.execute(command);
        } catch (ExecuteException e) {
            throw new IOException("cannot run " + command + ": " + e.getMessage(), e);
        }
        String text = output.toString(Charset.defaultCharset());
        if (watchdog.killedProcess()) {
            throw new IOException(command + " did not finish within " + VERSION_TIMEOUT.toSeconds() + " s");
        }
        return parseVersion(text).orElseThrow(() -> new IOException(command + " printed no version: "
                + firstLine(text)));
    }

    /** The version in TRON's help text, if there is one. */
    static Optional<String> parseVersion(String text) {
        for (String line : text.split("\\R")) {
            String lower = line.toLowerCase(Locale.ROOT);
            if (lower.contains("tron") || lower.contains("version")) {
                Matcher m = VERSION.matcher(line);
                if (m.find()) {
                    return Optional.of(m.group(1).trim());
                }
            }
        }
        return Optional.empty();
    }

    private static String firstLine(String text) {
        String trimmed = text.strip();
        if (trimmed.isEmpty()) {
            return "(nothing)";
        }
        return "'" + trimmed.split("\\R", 2)[0] + "'";
    }

    /** The places to look, in order. */
    List<Path> candidates() {
        List<Path> out = new ArrayList<>();
        String name = executableName();
        String home = variable(TRON_HOME);
        if (home != null && !home.isBlank()) {
            addIfValid(out, home.strip(), "bin", name);
            addIfValid(out, home.strip(), name);
        }
        String path = variable("PATH");
        if (path != null) {
            for (String dir : path.split(windows ? ";" : ":")) {
                if (!dir.isBlank()) {
                    addIfValid(out, unquote(dir.strip()), name);
                }
            }
        }
        return out;
    }

    private static void addIfValid(List<Path> out, String first, String... more) {
        try {
            out.add(Path.of(first, more));
        } catch (InvalidPathException e) {
            LOG.debug("skipping {}: {}", first, e.getMessage());
        }
    }

    private static String unquote(String dir) {
        return dir.length() >= 2 && dir.startsWith("\"") && dir.endsWith("\"") ? dir.substring(1, dir.length() - 1)
                : dir;
    }

    private String variable(String name) {
        if (!windows) {
            return env.get(name);
        }
        for (Map.Entry<String, String> e : env.entrySet()) {
            if (e.getKey().equalsIgnoreCase(name)) {
                return e.getValue();
            }
        }
        return null;
    }

    private boolean isExecutable(Path file) {
        return Files.isRegularFile(file) && (windows || Files.isExecutable(file));
    }
}
