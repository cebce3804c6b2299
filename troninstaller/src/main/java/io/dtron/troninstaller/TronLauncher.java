package io.dtron.troninstaller;

import java.io.File;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Objects;
import org.apache.commons.exec.CommandLine;
import org.apache.commons.exec.DefaultExecuteResultHandler;
import org.apache.commons.exec.DefaultExecutor;
import org.apache.commons.exec.ExecuteWatchdog;
import org.apache.commons.exec.PumpStreamHandler;
import org.apache.commons.exec.ShutdownHookProcessDestroyer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Launches an installed TRON with commons-exec: {@code tron -I SocketAdapter [options] MODEL -- HOST PORT}. TRON's
 * standard output and error are collected (and echoed to a stream of the caller's choice); a watchdog ends TRON
 * after a time limit, and TRON is ended with the JVM.
 */
public final class TronLauncher {
    private static final Logger LOG = LoggerFactory.getLogger(TronLauncher.class);

    private final Path executable;

    /** A launcher for the executable found by {@link TronInstallation}. */
    public TronLauncher(Path executable) {
        this.executable = Objects.requireNonNull(executable, "executable");
    }

    /** A launcher for the installed TRON. */
    public static TronLauncher installed(TronInstallation installation) throws TronNotFoundException {
        return new TronLauncher(installation.require());
    }

    /** The command line that {@link #start} runs. Arguments are passed as they are, without shell quoting. */
    public CommandLine commandLine(TronArguments arguments) {
        CommandLine command = new CommandLine(executable.toFile());
        for (String arg : arguments.toList()) {
            command.addArgument(arg, false);
        }
        return command;
    }

    /**
     * Starts TRON. Its output goes to the returned handle and, as it comes, to {@code echo} (or nowhere when null).
     *
     * @param limit TRON is ended after this long
     * @throws IOException when TRON cannot be started
     */
    public RunningTron start(TronArguments arguments, OutputStream echo, Duration limit) throws IOException {
        CommandLine command = commandLine(arguments);
        RunningTron.Output output = new RunningTron.Output(echo);
        ExecuteWatchdog watchdog = ExecuteWatchdog.builder().setTimeout(limit).get();
        DefaultExecutor executor = DefaultExecutor.builder()
                .setExecuteStreamHandler(new PumpStreamHandler(output))
                .setWorkingDirectory(workingDirectory(arguments.model()))
                .get();
        executor.setWatchdog(watchdog);
        executor.setExitValues(null);
        executor.setProcessDestroyer(new ShutdownHookProcessDestroyer());
        DefaultExecuteResultHandler result = new DefaultExecuteResultHandler();
        LOG.info("starting {}", String.join(" ", command.toStrings()));
        executor.execute(command, result);
        return new RunningTron(command, output, watchdog, result);
    }

    private static File workingDirectory(Path model) {
        Path parent = model.toAbsolutePath().getParent();
        return parent == null ? new File(".") : parent.toFile();
    }
}
